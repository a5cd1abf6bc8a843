#pragma once

#include "tilejet/config/section.hpp"
#include "tilejet/drivers/config.hpp"

// One parse function per section, for a loader that reads a file with more sections than the
// drivers own (the daemon's). Each takes the section's table (nullptr when absent) and throws on
// unknown keys and wrong types, naming file, section, key and line.
namespace tilejet::drivers {

LineConfig parse_line_section(const toml::table* table, const config::ConfigSource& source);
ModbusConfig parse_modbus_section(const toml::table* table, const config::ConfigSource& source);
GpioConfig parse_gpio_section(const toml::table* table, const config::ConfigSource& source);
SimConfig parse_sim_section(const toml::table* table, const config::ConfigSource& source);

// Parses the drivers' sections of an already-loaded file.
DriversConfig parse_drivers_config(const toml::table& root, const config::ConfigSource& source);

}  // namespace tilejet::drivers
