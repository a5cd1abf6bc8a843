#pragma once

#include <toml++/toml.h>

#include <cstdint>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "tilejet/config/source.hpp"

namespace tilejet::config {

// The [name] section of a file: its table, or nullptr when the file has none. A key of that name
// that is not a table is an error naming the file and line.
const toml::table* find_section(const toml::table& root, const char* name,
                                const ConfigSource& source);

// One [section] of a TOML config, read key by key. Every key read is remembered, so finish()
// can reject the keys nobody asked for: a typo in a key is an error, never a silent default
// (Klipper's habit). An absent section reads as empty, so every key takes its default.
class ConfigSection {
  public:
    ConfigSection(const toml::table* table, ConfigSource source, std::string name);

    std::string get_string(std::string_view key, std::string fallback);
    std::string require_string(std::string_view key);
    std::int64_t get_int(std::string_view key, std::int64_t fallback, std::int64_t min,
                         std::int64_t max);
    std::int64_t require_int(std::string_view key, std::int64_t min, std::int64_t max);
    double get_double(std::string_view key, double fallback, double min, double max);
    bool get_bool(std::string_view key, bool fallback);
    // The value must be one of `choices`; an empty fallback makes the key required.
    std::string get_choice(std::string_view key, std::string fallback,
                           const std::vector<std::string>& choices);

    // Throws naming the first key that no get_ or require_ call consumed.
    void finish() const;

    // "file:line: [section] key: message", with the key's line when it exists.
    [[noreturn]] void fail(std::string_view key, const std::string& message) const;
    const ConfigSource& source() const { return source_; }

  private:
    const toml::node* find(std::string_view key);
    std::int64_t checked_int(std::string_view key, const toml::node& node, std::int64_t min,
                             std::int64_t max) const;

    const toml::table* table_;
    ConfigSource source_;
    std::string name_;
    std::set<std::string, std::less<>> used_;
};

}  // namespace tilejet::config
