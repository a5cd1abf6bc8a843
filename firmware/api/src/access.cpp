#include "tilejet/api/access.hpp"

#include "tilejet/config/enum_names.hpp"

namespace tilejet::api {

namespace {

constexpr config::EnumNames kRoles{std::array<std::pair<Role, std::string_view>, 3>{{
    {Role::viewer, "viewer"},
    {Role::operator_, "operator"},
    {Role::engineer, "engineer"},
}}};

}  // namespace

std::optional<Role> parse_role(std::string_view text) {
    return kRoles.parse(text);
}

std::string_view to_string(Role role) {
    return kRoles.name(role);
}

std::vector<std::string> role_names() {
    return kRoles.names();
}

}  // namespace tilejet::api
