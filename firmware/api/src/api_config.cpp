#include "tilejet/api/api_config.hpp"

#include <stdexcept>

#include "tilejet/api/password.hpp"
#include "tilejet/config/section.hpp"

namespace tilejet::api {

namespace {

ApiConfig parse_api(const toml::table* t, const config::ConfigSource& src) {
    config::ConfigSection s(t, src, "api");
    ApiConfig c;
    c.host = s.get_string("host", c.host);
    c.port = int(s.get_int("port", c.port, 0, 65535));
    auto& a = c.access;
    a.sessions.idle = std::chrono::minutes(
        s.get_int("session_idle_minutes", a.sessions.idle.count() / 60, 1, 7 * 24 * 60));
    a.sessions.lifetime = std::chrono::hours(s.get_int(
        "session_hours",
        std::chrono::duration_cast<std::chrono::hours>(a.sessions.lifetime).count(), 1, 7 * 24));
    a.sign_in.failures_per_user =
        int(s.get_int("sign_in_failures_per_user", a.sign_in.failures_per_user, 1, 1000));
    a.sign_in.failures_per_address =
        int(s.get_int("sign_in_failures_per_address", a.sign_in.failures_per_address, 1, 10000));
    a.sign_in.window =
        std::chrono::seconds(s.get_int("sign_in_window_s", a.sign_in.window.count(), 1, 24 * 3600));
    auto& l = a.limits;
    l.connections = int(s.get_int("connections", l.connections, 8, 4096));
    l.connections_per_address =
        int(s.get_int("connections_per_address", l.connections_per_address, 4, 4096));
    l.header_timeout =
        std::chrono::seconds(s.get_int("header_timeout_s", l.header_timeout.count(), 1, 300));
    l.body_timeout =
        std::chrono::seconds(s.get_int("body_timeout_s", l.body_timeout.count(), 1, 3600));
    l.event_streams = int(s.get_int("event_streams", l.event_streams, 1, 1024));
    l.event_streams_per_session =
        int(s.get_int("event_streams_per_session", l.event_streams_per_session, 1, 64));
    // The names the API answers to besides the loopback ones: the address it listens on and
    // what the line's browsers call the controller ("controller.line.local, 10.0.0.5").
    const auto bracketed = [](const std::string& h) {
        return h.find(':') != std::string::npos && !h.starts_with('[') ? "[" + h + "]" : h;
    };
    a.host_names.push_back(bracketed(c.host));
    std::string names = s.get_string("host_names", "");
    for (size_t at = 0; at < names.size();) {
        size_t end = names.find(',', at);
        if (end == std::string::npos) end = names.size();
        std::string name = names.substr(at, end - at);
        name.erase(0, name.find_first_not_of(' '));
        name.erase(name.find_last_not_of(' ') + 1);
        if (!name.empty()) a.host_names.push_back(bracketed(name));
        at = end + 1;
    }
    s.finish();
    return c;
}

// [[users]]: name, role, password_hash (tilejet passwd makes the hash).
std::vector<User> parse_users(const toml::table& root, const config::ConfigSource& src) {
    std::vector<User> users;
    const toml::node* node = root.get("users");
    if (!node) return users;
    const toml::array* list = node->as_array();
    if (!list || !list->is_array_of_tables())
        throw std::runtime_error(src.file + ":" + std::to_string(node->source().begin.line) +
                                 ": 'users' must be [[users]] tables");
    for (const toml::node& entry : *list) {
        config::ConfigSection s(entry.as_table(), src, "users");
        User u;
        u.name = s.require_string("name");
        if (u.name.empty() || u.name.size() > 64 ||
            u.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                     "0123456789._-") != std::string::npos)
            s.fail("name", "'" + u.name + "': 1..64 letters, digits, '.', '_' or '-'");
        u.role = *parse_role(s.get_choice("role", "", role_names()));
        u.password_hash = s.require_string("password_hash");
        try {
            check_password_hash(u.password_hash);
        } catch (const std::exception& e) {
            s.fail("password_hash", e.what());
        }
        for (const User& other : users)
            if (other.name == u.name) s.fail("name", "user '" + u.name + "' appears twice");
        s.finish();
        users.push_back(std::move(u));
    }
    return users;
}

}  // namespace

ApiConfig parse_api_config(const toml::table& root, const config::ConfigSource& src) {
    ApiConfig c = parse_api(config::find_section(root, "api", src), src);
    c.access.users = parse_users(root, src);
    return c;
}

}  // namespace tilejet::api
