#include "daemon_config.hpp"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "tilejet/api/password.hpp"
#include "tilejet/drivers/config_parse.hpp"

namespace tilejet::daemon {

namespace {

using drivers::ConfigSection;
using drivers::ConfigSource;

constexpr std::array<const char*, 6> kDaemonSections{"colour", "storage", "api",
                                                     "users",  "render",  "print"};

const toml::table* section(const toml::table& root, const char* name, const ConfigSource& src) {
    const toml::node* node = root.get(name);
    if (!node) return nullptr;
    if (!node->is_table())
        throw std::runtime_error(src.file + ":" + std::to_string(node->source().begin.line) +
                                 ": '" + name + "' must be a [" + name + "] section");
    return node->as_table();
}

std::string resolve(const ConfigSource& src, const std::string& path) {
    if (path.empty() || std::filesystem::path(path).is_absolute()) return path;
    return (std::filesystem::path(src.file).parent_path() / path).lexically_normal().string();
}

colour::ColourSettings parse_colour(const toml::table* t, const ConfigSource& src) {
    ConfigSection s(t, src, "colour");
    colour::ColourSettings c;
    c.output_profile = resolve(src, s.require_string("output_profile"));
    c.source_profile = resolve(src, s.get_string("source_profile", ""));
    const std::string intent =
        s.get_choice("intent", "perceptual", {"perceptual", "relative", "saturation", "absolute"});
    c.intent = *colour::parse_intent(intent);
    c.black_point_compensation = s.get_bool("black_point_compensation", false);
    c.ink_limit_percent = s.get_double("ink_limit_percent", 300, 0, 400);
    c.ink_curves = resolve(src, s.get_string("ink_curves", ""));
    if (!std::filesystem::exists(c.output_profile))
        s.fail("output_profile", "no such file '" + c.output_profile.string() + "'");
    s.finish();
    return c;
}

StorageConfig parse_storage(const toml::table* t, const ConfigSource& src) {
    ConfigSection s(t, src, "storage");
    StorageConfig c;
    c.database = resolve(src, s.get_string("database", c.database));
    c.previews = resolve(src, s.get_string("previews", c.previews));
    c.preview_tiles = int(s.get_int("preview_tiles", c.preview_tiles, 0, 1000));
    c.designs = resolve(src, s.get_string("designs", ""));
    c.profiles = resolve(src, s.get_string("profiles", ""));
    s.finish();
    return c;
}

ApiConfig parse_api(const toml::table* t, const ConfigSource& src) {
    ConfigSection s(t, src, "api");
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
std::vector<api::User> parse_users(const toml::table& root, const ConfigSource& src) {
    std::vector<api::User> users;
    const toml::node* node = root.get("users");
    if (!node) return users;
    const toml::array* list = node->as_array();
    if (!list || !list->is_array_of_tables())
        throw std::runtime_error(src.file + ":" + std::to_string(node->source().begin.line) +
                                 ": 'users' must be [[users]] tables");
    for (const toml::node& entry : *list) {
        ConfigSection s(entry.as_table(), src, "users");
        api::User u;
        u.name = s.require_string("name");
        if (u.name.empty() || u.name.size() > 64 ||
            u.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                     "0123456789._-") != std::string::npos)
            s.fail("name", "'" + u.name + "': 1..64 letters, digits, '.', '_' or '-'");
        u.role = *api::parse_role(s.get_choice("role", "", {"viewer", "operator", "engineer"}));
        u.password_hash = s.require_string("password_hash");
        try {
            api::check_password_hash(u.password_hash);
        } catch (const std::exception& e) {
            s.fail("password_hash", e.what());
        }
        for (const api::User& other : users)
            if (other.name == u.name) s.fail("name", "user '" + u.name + "' appears twice");
        s.finish();
        users.push_back(std::move(u));
    }
    return users;
}

ApiConfig parse_api_and_users(const toml::table& root, const ConfigSource& src) {
    ApiConfig c = parse_api(section(root, "api", src), src);
    c.access.users = parse_users(root, src);
    return c;
}

RenderConfig parse_render(const toml::table* t, const ConfigSource& src) {
    ConfigSection s(t, src, "render");
    RenderConfig c;
    c.threads = int(s.get_int("threads", c.threads, 0, 256));
    c.queue_tiles = int(s.get_int("queue_tiles", c.queue_tiles, 1, 256));
    c.dpi = int(s.get_int("dpi", c.dpi, 10, 2400));
    s.finish();
    return c;
}

PrintConfig parse_print(const toml::table* t, const ConfigSource& src,
                        const drivers::DriversConfig& d) {
    ConfigSection s(t, src, "print");
    PrintConfig c;
    // The PLC's own limit, from the register map, bounds the speeds the daemon may ask for.
    const drivers::Register* setpoint = d.registers.find("speed_setpoint");
    const std::int64_t fastest = setpoint ? setpoint->max : 0xffff;
    c.speed_mm_s =
        int(s.get_int("speed_mm_s", std::min<std::int64_t>(c.speed_mm_s, fastest), 1, fastest));
    c.min_speed_mm_s = int(s.get_int("min_speed_mm_s", c.min_speed_mm_s, 1, fastest));
    c.poll = std::chrono::milliseconds(s.get_int("poll_ms", 5, 1, 1000));
    c.send_timeout = std::chrono::milliseconds(s.get_int("send_timeout_ms", 1000, 10, 60000));
    c.send_margin = std::chrono::milliseconds(s.get_int("send_margin_ms", 20, 0, 10000));
    c.drain_timeout = std::chrono::seconds(s.get_int("drain_timeout_s", 30, 0, 3600));
    // The simulated heads' buffer is configured in [sim]; real heads would say it here.
    c.head_buffer_tiles = int(
        s.get_int("head_buffer_tiles", d.line.heads == "sim" ? d.sim.head_buffer_tiles : 2, 1, 64));
    if (c.min_speed_mm_s > c.speed_mm_s) s.fail("min_speed_mm_s", "must be at most speed_mm_s");
    s.finish();
    return c;
}

}  // namespace

DaemonConfig load_daemon_config(const std::string& path) {
    const toml::table root = drivers::load_toml_file(path);
    const ConfigSource src{path};
    for (const auto& [key, node] : root) {
        // A named copy: lambdas may not capture structured bindings before C++20's P1091 (clang
        // 14).
        const std::string_view name = key.str();
        const auto known = [&](const auto& list) {
            return std::find(list.begin(), list.end(), name) != list.end();
        };
        if (!known(drivers::kDriverSections) && !known(kDaemonSections))
            throw std::runtime_error(path + ":" + std::to_string(node.source().begin.line) + ": [" +
                                     std::string(key.str()) + "]: unknown section");
    }
    drivers::DriversConfig d = drivers::parse_drivers_config(root, src);
    PrintConfig print = parse_print(section(root, "print", src), src, d);
    return DaemonConfig{
        .file = path,
        .drivers = std::move(d),
        .colour = parse_colour(section(root, "colour", src), src),
        .storage = parse_storage(section(root, "storage", src), src),
        .api = parse_api_and_users(root, src),
        .render = parse_render(section(root, "render", src), src),
        .print = print,
    };
}

}  // namespace tilejet::daemon
