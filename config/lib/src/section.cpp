#include "tilejet/config/section.hpp"

#include <sstream>
#include <stdexcept>

namespace tilejet::config {

namespace {

std::string type_name(const toml::node& node) {
    std::ostringstream s;
    s << node.type();
    return s.str();
}

}  // namespace

const toml::table* find_section(const toml::table& root, const char* name,
                                const ConfigSource& source) {
    const toml::node* node = root.get(name);
    if (!node) return nullptr;
    if (!node->is_table())
        throw std::runtime_error(source.file + ":" + std::to_string(node->source().begin.line) +
                                 ": '" + name + "' must be a [" + name + "] section");
    return node->as_table();
}

ConfigSection::ConfigSection(const toml::table* table, ConfigSource source, std::string name)
    : table_(table), source_(std::move(source)), name_(std::move(name)) {}

const toml::node* ConfigSection::find(std::string_view key) {
    used_.emplace(key);
    return table_ ? table_->get(key) : nullptr;
}

void ConfigSection::fail(std::string_view key, const std::string& message) const {
    std::ostringstream s;
    s << source_.file;
    const toml::node* node = table_ ? table_->get(key) : nullptr;
    if (node && node->source().begin.line)
        s << ':' << node->source().begin.line;
    else if (table_ && table_->source().begin.line)
        s << ':' << table_->source().begin.line;
    s << ": [" << name_ << "] " << key << ": " << message;
    throw std::runtime_error(s.str());
}

std::int64_t ConfigSection::checked_int(std::string_view key, const toml::node& node,
                                        std::int64_t min, std::int64_t max) const {
    if (!node.is_integer()) fail(key, "expected an integer, got " + type_name(node));
    const std::int64_t v = node.as_integer()->get();
    if (v < min || v > max)
        fail(key, "value " + std::to_string(v) + " is outside " + std::to_string(min) + ".." +
                      std::to_string(max));
    return v;
}

std::string ConfigSection::get_string(std::string_view key, std::string fallback) {
    const toml::node* node = find(key);
    if (!node) return fallback;
    if (!node->is_string()) fail(key, "expected a string, got " + type_name(*node));
    return node->as_string()->get();
}

std::string ConfigSection::require_string(std::string_view key) {
    if (!find(key)) fail(key, "missing (required)");
    return get_string(key, {});
}

std::int64_t ConfigSection::get_int(std::string_view key, std::int64_t fallback, std::int64_t min,
                                    std::int64_t max) {
    const toml::node* node = find(key);
    return node ? checked_int(key, *node, min, max) : fallback;
}

std::int64_t ConfigSection::require_int(std::string_view key, std::int64_t min, std::int64_t max) {
    const toml::node* node = find(key);
    if (!node) fail(key, "missing (required)");
    return checked_int(key, *node, min, max);
}

double ConfigSection::get_double(std::string_view key, double fallback, double min, double max) {
    const toml::node* node = find(key);
    if (!node) return fallback;
    double v = 0;
    if (node->is_floating_point())
        v = node->as_floating_point()->get();
    else if (node->is_integer())
        v = double(node->as_integer()->get());
    else
        fail(key, "expected a number, got " + type_name(*node));
    if (!(v >= min && v <= max))
        fail(key, "value " + std::to_string(v) + " is outside " + std::to_string(min) + ".." +
                      std::to_string(max));
    return v;
}

bool ConfigSection::get_bool(std::string_view key, bool fallback) {
    const toml::node* node = find(key);
    if (!node) return fallback;
    if (!node->is_boolean()) fail(key, "expected true or false, got " + type_name(*node));
    return node->as_boolean()->get();
}

std::string ConfigSection::get_choice(std::string_view key, std::string fallback,
                                      const std::vector<std::string>& choices) {
    const bool required = fallback.empty();
    if (required && !(table_ && table_->get(key))) {
        used_.emplace(key);
        fail(key, "missing (required)");
    }
    std::string v = get_string(key, std::move(fallback));
    for (const auto& c : choices)
        if (v == c) return v;
    std::string list;
    for (const auto& c : choices)
        list += (list.empty() ? "" : ", ") + ('"' + c + '"');
    fail(key, "\"" + v + "\" is not one of " + list);
}

void ConfigSection::finish() const {
    if (!table_) return;
    for (const auto& [key, node] : *table_)
        if (!used_.contains(key.str())) fail(key.str(), "unknown key");
}

}  // namespace tilejet::config
