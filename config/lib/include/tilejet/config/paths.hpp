#pragma once

#include <string>

#include "tilejet/config/source.hpp"

namespace tilejet::config {

// A path as a config file states it, resolved against the file's folder, so that a config and
// the files it names can move together. Absolute paths stay; an empty one stays empty (it means
// "none" wherever a path is optional).
std::string resolve_path(const ConfigSource& source, const std::string& path);

}  // namespace tilejet::config
