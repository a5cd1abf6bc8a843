#pragma once

// The config file's [api] section and its [[users]]: where the HTTP API and panel listen, who
// may sign in, and the session, sign-in and connection limits.
#include <toml++/toml.h>

#include <array>
#include <string>

#include "tilejet/api/access.hpp"
#include "tilejet/config/source.hpp"

namespace tilejet::api {

struct ApiConfig {
    std::string host = "127.0.0.1";
    int port = 8470;        // 0: the kernel picks (tests); the daemon logs the port it got
    AccessSettings access;  // users from [[users]], the rest from [api]
};

inline constexpr std::array<const char*, 2> kApiSections{"api", "users"};

// Reads [api] and [[users]] of an already-loaded file (absent ones take their defaults).
ApiConfig parse_api_config(const toml::table& root, const config::ConfigSource& source);

}  // namespace tilejet::api
