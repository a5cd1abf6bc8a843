#include "tilejet/api/access.hpp"

namespace tilejet::api {

std::optional<Role> parse_role(std::string_view text) {
    if (text == "viewer") return Role::viewer;
    if (text == "operator") return Role::operator_;
    if (text == "engineer") return Role::engineer;
    return std::nullopt;
}

std::string_view to_string(Role role) {
    switch (role) {
        case Role::viewer:
            return "viewer";
        case Role::operator_:
            return "operator";
        case Role::engineer:
            return "engineer";
    }
    return "?";
}

}  // namespace tilejet::api
