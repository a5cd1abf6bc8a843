#pragma once

#include <toml++/toml.h>

#include <string>

namespace tilejet::config {

// Parses a whole TOML file; a syntax error names the file, line and column.
toml::table load_toml_file(const std::string& path);

}  // namespace tilejet::config
