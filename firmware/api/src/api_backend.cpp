// What a backend that has no pictures, designs or config to offer answers: 501, so a test
// backend (or a future one) implements only what it needs.
#include "tilejet/api/api_backend.hpp"

#include "tilejet/api/job_request.hpp"

namespace tilejet::api {

namespace {
[[noreturn]] void not_offered(const char* what) {
    throw ApiError(501, "", std::string(what) + ": not offered by this server");
}
}  // namespace

std::string ApiBackend::tile_png(std::int64_t, std::int64_t, int) {
    not_offered("tile pictures");
}
std::string ApiBackend::wall_png(int, int) {
    not_offered("wall preview");
}
nlohmann::json ApiBackend::designs() {
    return nlohmann::json::array();
}
nlohmann::json ApiBackend::profiles() {
    return nlohmann::json::array();
}
nlohmann::json ApiBackend::add_design(const std::string&, const std::string&) {
    not_offered("design upload");
}
nlohmann::json ApiBackend::add_profile(const std::string&, const std::string&) {
    not_offered("profile upload");
}
nlohmann::json ApiBackend::reload_config() {
    not_offered("config reload");
}

}  // namespace tilejet::api
