#pragma once

#include <string>

namespace tilejet::config {

// Where a section came from, for error messages: "config/tilejet.toml:14: [modbus] port: ...".
struct ConfigSource {
    std::string file;
};

}  // namespace tilejet::config
