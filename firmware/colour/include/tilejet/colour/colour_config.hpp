#pragma once

// The config file's [colour] section: the line's colour pipeline, for every job's transform.
#include <toml++/toml.h>

#include "tilejet/colour/colour_settings.hpp"
#include "tilejet/config/source.hpp"

namespace tilejet::colour {

inline constexpr const char* kColourSection = "colour";

// Takes the section's table (nullptr when absent: output_profile is required, so that is an
// error). Relative paths resolve against the config file's folder; the output profile must exist.
ColourSettings parse_colour_section(const toml::table* table, const config::ConfigSource& source);

}  // namespace tilejet::colour
