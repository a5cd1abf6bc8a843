#include "daemon_config.hpp"

#include <algorithm>
#include <array>
#include <string_view>
#include <vector>

#include "tilejet/colour/colour_config.hpp"
#include "tilejet/config/known_sections.hpp"
#include "tilejet/config/paths.hpp"
#include "tilejet/config/section.hpp"
#include "tilejet/config/toml_file.hpp"
#include "tilejet/drivers/config_parse.hpp"

namespace tilejet::daemon {

namespace {

using config::ConfigSection;
using config::ConfigSource;
using config::resolve_path;

constexpr std::array<const char*, 3> kDaemonSections{"storage", "render", "print"};

StorageConfig parse_storage(const toml::table* t, const ConfigSource& src) {
    ConfigSection s(t, src, "storage");
    StorageConfig c;
    c.database = resolve_path(src, s.get_string("database", c.database));
    c.previews = resolve_path(src, s.get_string("previews", c.previews));
    c.preview_tiles = int(s.get_int("preview_tiles", c.preview_tiles, 0, 1000));
    c.designs = resolve_path(src, s.get_string("designs", ""));
    c.profiles = resolve_path(src, s.get_string("profiles", ""));
    s.finish();
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
    const toml::table root = config::load_toml_file(path);
    const ConfigSource src{path};
    std::vector<std::string_view> known(drivers::kDriverSections.begin(),
                                        drivers::kDriverSections.end());
    known.push_back(colour::kColourSection);
    known.insert(known.end(), api::kApiSections.begin(), api::kApiSections.end());
    known.insert(known.end(), kDaemonSections.begin(), kDaemonSections.end());
    config::reject_unknown_sections(root, known, src);
    drivers::DriversConfig d = drivers::parse_drivers_config(root, src);
    PrintConfig print = parse_print(config::find_section(root, "print", src), src, d);
    return DaemonConfig{
        .file = path,
        .drivers = std::move(d),
        .colour = colour::parse_colour_section(config::find_section(root, "colour", src), src),
        .storage = parse_storage(config::find_section(root, "storage", src), src),
        .api = api::parse_api_config(root, src),
        .render = parse_render(config::find_section(root, "render", src), src),
        .print = print,
    };
}

}  // namespace tilejet::daemon
