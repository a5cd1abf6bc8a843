#include <unistd.h>

#include <cstdlib>

#include "tilejet/config/paths.hpp"
#include "tilejet/config/toml_file.hpp"
#include "tilejet/drivers/config_parse.hpp"

namespace tilejet::drivers {

std::string_view config_key(GpioInput input) {
    switch (input) {
        case GpioInput::photo_eye:
            return "photo_eye";
        case GpioInput::estop:
            return "estop";
        case GpioInput::head_ready:
            return "head_ready";
    }
    return "?";
}

std::string_view config_key(GpioOutput output) {
    return output == GpioOutput::print_enable ? "print_enable" : "beacon";
}

std::string_view to_string(GpioInput input) {
    return config_key(input);
}
std::string_view to_string(GpioOutput output) {
    return config_key(output);
}

LineConfig parse_line_section(const toml::table* table, const config::ConfigSource& source) {
    config::ConfigSection s(table, source, "line");
    LineConfig c;
    c.tile_length_mm = s.get_double("tile_length_mm", c.tile_length_mm, 1, 10000);
    c.tile_pitch_mm = s.get_double("tile_pitch_mm", c.tile_pitch_mm, 1, 20000);
    c.photo_eye_mm = s.get_double("photo_eye_mm", c.photo_eye_mm, 0, 100000);
    c.heads_mm = s.get_double("heads_mm", c.heads_mm, 0, 100000);
    c.control = s.get_choice("control", c.control, {"modbus"});
    c.heads = s.get_choice("heads", c.heads, {"sim"});
    c.register_map = s.get_string("register_map", c.register_map);
    if (c.tile_pitch_mm <= c.tile_length_mm)
        s.fail("tile_pitch_mm", "must be larger than tile_length_mm (tiles would touch)");
    if (c.heads_mm <= c.photo_eye_mm)
        s.fail("heads_mm",
               "the heads must sit downstream of the photo-eye (heads_mm > photo_eye_mm)");
    s.finish();
    return c;
}

ModbusConfig parse_modbus_section(const toml::table* table, const config::ConfigSource& source) {
    config::ConfigSection s(table, source, "modbus");
    ModbusConfig c;
    c.transport = s.get_choice("transport", c.transport, {"tcp", "rtu"});
    c.host = s.get_string("host", c.host);
    c.port = int(s.get_int("port", c.port, 0, 65535));
    c.device = s.get_string("device", c.device);
    c.baud = int(s.get_int("baud", c.baud, 1200, 1000000));
    c.parity = s.get_choice("parity", std::string(1, c.parity), {"N", "E", "O"})[0];
    c.data_bits = int(s.get_int("data_bits", c.data_bits, 5, 8));
    c.stop_bits = int(s.get_int("stop_bits", c.stop_bits, 1, 2));
    c.unit_id = int(s.get_int("unit_id", c.unit_id, 0, 247));
    c.response_timeout = std::chrono::milliseconds(s.get_int("response_timeout_ms", 200, 1, 60000));
    c.reconnect_min = std::chrono::milliseconds(s.get_int("reconnect_min_ms", 50, 1, 60000));
    c.reconnect_max = std::chrono::milliseconds(s.get_int("reconnect_max_ms", 500, 1, 600000));
    if (c.reconnect_max < c.reconnect_min)
        s.fail("reconnect_max_ms", "must be at least reconnect_min_ms");
    s.finish();
    return c;
}

GpioConfig parse_gpio_section(const toml::table* table, const config::ConfigSource& source) {
    config::ConfigSection s(table, source, "gpio");
    GpioConfig c;
    c.backend = s.get_choice("backend", c.backend, {"sim", "gpiod"});
    c.chip = s.get_string("chip", c.chip);
    for (size_t i = 0; i < kGpioInputs.size(); ++i) {
        const std::string key(config_key(kGpioInputs[i]));
        c.input_names[i] = s.get_string(key, c.input_names[i]);
        c.input_active_low[i] = s.get_bool(key + "_active_low", c.input_active_low[i]);
    }
    for (size_t i = 0; i < kGpioOutputs.size(); ++i)
        c.output_names[i] = s.get_string(config_key(kGpioOutputs[i]), c.output_names[i]);
    c.debounce = std::chrono::microseconds(s.get_int("debounce_us", 2000, 0, 1000000));
    s.finish();
    return c;
}

std::string sim_runtime_directory() {
    if (const char* d = std::getenv("RUNTIME_DIRECTORY"); d && *d == '/')
        return std::string(d).substr(0, std::string(d).find(':'));  // the first of several
    if (const char* d = std::getenv("XDG_RUNTIME_DIR"); d && *d == '/')
        return std::string(d) + "/tilejet-sim";
    return "/tmp/tilejet-sim-" + std::to_string(::getuid());
}

SimConfig parse_sim_section(const toml::table* table, const config::ConfigSource& source) {
    config::ConfigSection s(table, source, "sim");
    SimConfig c;
    const auto socket = [&](const char* key, const std::string& fallback) {
        const std::string path = s.get_string(key, fallback);
        return path.find('/') == std::string::npos ? sim_runtime_directory() + "/" + path : path;
    };
    c.gpio_socket = socket("gpio_socket", c.gpio_socket);
    c.head_socket = socket("head_socket", c.head_socket);
    c.control_socket = socket("control_socket", c.control_socket);
    c.speed_mm_s = int(s.get_int("speed_mm_s", c.speed_mm_s, 0, 0xffff));
    c.start_running = s.get_bool("start_running", c.start_running);
    c.head_buffer_tiles = int(s.get_int("head_buffer_tiles", c.head_buffer_tiles, 1, 64));
    c.head_checksums = s.get_bool("head_checksums", c.head_checksums);
    s.finish();
    return c;
}

DriversConfig parse_drivers_config(const toml::table& root, const config::ConfigSource& source) {
    LineConfig line = parse_line_section(config::find_section(root, "line", source), source);
    RegisterMap registers = load_register_map(config::resolve_path(source, line.register_map));
    return DriversConfig{
        .file = source.file,
        .line = std::move(line),
        .modbus = parse_modbus_section(config::find_section(root, "modbus", source), source),
        .gpio = parse_gpio_section(config::find_section(root, "gpio", source), source),
        .sim = parse_sim_section(config::find_section(root, "sim", source), source),
        .registers = std::move(registers),
    };
}

DriversConfig load_drivers_config(const std::string& path) {
    return parse_drivers_config(config::load_toml_file(path), config::ConfigSource{path});
}

}  // namespace tilejet::drivers
