#pragma once

#include <toml++/toml.h>

#include <string_view>
#include <vector>

#include "tilejet/config/source.hpp"

namespace tilejet::config {

// Throws "file:line: [name]: unknown section" for the first top-level key not in `known`: each
// module parses only its own sections, so only the one composing them knows the whole list.
void reject_unknown_sections(const toml::table& root, const std::vector<std::string_view>& known,
                             const ConfigSource& source);

}  // namespace tilejet::config
