#pragma once

// Salted password hashes for the config's [[users]]: PBKDF2-HMAC-SHA256 (OpenSSL), stored as
// "pbkdf2-sha256$ITERATIONS$SALT$HASH" (salt and hash in base64). The iteration count travels
// with the hash, so raising the default later leaves existing hashes valid.
#include <string>
#include <string_view>

namespace tilejet::api {

// OWASP's 2023 figure for PBKDF2-HMAC-SHA256: about 0.3 s of one core per sign-in here, which
// the sign-in rate limit keeps from becoming a way to load the daemon.
inline constexpr int kPasswordIterations = 600'000;

// A fresh random salt each call.
std::string hash_password(std::string_view password, int iterations = kPasswordIterations);

// Constant-time comparison. Throws std::invalid_argument when `hash` is not in the format
// above (a config error, reported at start-up rather than at the first sign-in).
bool verify_password(std::string_view password, std::string_view hash);

// Throws std::invalid_argument naming what is wrong with the hash text.
void check_password_hash(std::string_view hash);

}  // namespace tilejet::api
