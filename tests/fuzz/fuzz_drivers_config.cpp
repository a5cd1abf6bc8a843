// libFuzzer: the TOML config sections the line drivers own ([line], [modbus], [gpio], [sim]).
#include <toml++/toml.h>

#include <cstdint>
#include <stdexcept>
#include <string_view>

#include "tilejet/drivers/config_parse.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace tilejet::drivers;
    try {
        const toml::table root =
            toml::parse(std::string_view(reinterpret_cast<const char*>(data), size),
                        std::string_view("fuzz.toml"));
        const tilejet::config::ConfigSource source{"fuzz.toml"};
        parse_line_section(root["line"].as_table(), source);
        parse_modbus_section(root["modbus"].as_table(), source);
        parse_gpio_section(root["gpio"].as_table(), source);
        parse_sim_section(root["sim"].as_table(), source);
    } catch (const toml::parse_error&) {
    } catch (const std::runtime_error&) {  // the drivers' config errors
    }
    return 0;
}
