#pragma once

#include "tilejet/drivers/config.hpp"
#include "tilejet/drivers/config_section.hpp"

// One parse function per section, for a loader that reads a file with more sections than the
// drivers own (the daemon's). Each takes the section's table (nullptr when absent) and throws on
// unknown keys and wrong types, naming file, section, key and line.
namespace tilejet::drivers {

LineConfig parse_line_section(const toml::table* table, const ConfigSource& source);
ModbusConfig parse_modbus_section(const toml::table* table, const ConfigSource& source);
GpioConfig parse_gpio_section(const toml::table* table, const ConfigSource& source);
SimConfig parse_sim_section(const toml::table* table, const ConfigSource& source);

// Parses the drivers' sections of an already-loaded file.
DriversConfig parse_drivers_config(const toml::table& root, const ConfigSource& source);

}  // namespace tilejet::drivers
