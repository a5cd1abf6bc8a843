#include "tilejet/drivers/register_map.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "tilejet/config/section.hpp"
#include "tilejet/config/toml_file.hpp"

namespace tilejet::drivers {

namespace {

// The registers LineControl reads or writes by name; anything else in the map is served and can
// be read by name, but the daemon does not depend on it.
struct Required {
    const char* name;
    RegisterTable table;
};
constexpr Required kRequired[] = {
    {"ready", RegisterTable::input},
    {"running", RegisterTable::input},
    {"fault_code", RegisterTable::input},
    {"speed_actual", RegisterTable::input},
    {"tile_counter", RegisterTable::input},
    {"estop", RegisterTable::input},
    {"speed_setpoint", RegisterTable::holding},
    {"run_command", RegisterTable::holding},
};

std::uint32_t type_max(RegisterType t) {
    switch (t) {
        case RegisterType::boolean:
            return 1;
        case RegisterType::u16:
            return 0xffff;
        case RegisterType::u32:
            return 0xffffffff;
    }
    return 0;
}

Register parse_register(config::ConfigSection& s) {
    Register r;
    r.name = s.require_string("name");
    r.table = s.get_choice("table", "", {"input", "holding"}) == "input" ? RegisterTable::input
                                                                         : RegisterTable::holding;
    r.address = std::uint16_t(s.require_int("address", 0, 0xffff));
    const std::string type = s.get_choice("type", "", {"bool", "u16", "u32"});
    r.type = type == "bool"  ? RegisterType::boolean
             : type == "u16" ? RegisterType::u16
                             : RegisterType::u32;
    r.unit = s.get_string("unit", "");
    r.meaning = s.require_string("meaning");
    r.max = std::uint32_t(s.get_int("max", type_max(r.type), 0, type_max(r.type)));
    r.retain = s.get_bool("retain", false);
    if (r.address + r.words() > 0x10000) s.fail("address", "register runs past address 65535");
    if (r.retain && !r.writable()) s.fail("retain", "only holding registers can be retained");
    s.finish();
    return r;
}

}  // namespace

std::string Register::label() const {
    return std::string(to_string(table)) + " register " + std::to_string(address) + " '" + name +
           "'";
}

std::string_view to_string(RegisterTable table) {
    return table == RegisterTable::input ? "input" : "holding";
}

std::string_view to_string(RegisterType type) {
    switch (type) {
        case RegisterType::boolean:
            return "bool";
        case RegisterType::u16:
            return "u16";
        case RegisterType::u32:
            return "u32";
    }
    return "?";
}

RegisterMap::RegisterMap(std::vector<Register> registers, std::string source)
    : registers_(std::move(registers)), source_(std::move(source)) {
    for (size_t i = 0; i < registers_.size(); ++i) {
        const Register& a = registers_[i];
        for (size_t j = 0; j < i; ++j) {
            const Register& b = registers_[j];
            if (a.name == b.name)
                throw std::runtime_error(source_ + ": register '" + a.name + "' is defined twice");
            const bool overlap = a.table == b.table && a.address < b.address + b.words() &&
                                 b.address < a.address + a.words();
            if (overlap)
                throw std::runtime_error(source_ + ": " + a.label() + " overlaps " + b.label());
        }
    }
    for (const Required& r : kRequired) {
        const Register* reg = find(r.name);
        if (!reg)
            throw std::runtime_error(source_ + ": the map has no register '" + r.name +
                                     "' (LineControl needs it)");
        if (reg->table != r.table)
            throw std::runtime_error(source_ + ": register '" + r.name + "' must be an " +
                                     std::string(to_string(r.table)) + " register");
    }
}

const Register* RegisterMap::find(std::string_view name) const {
    for (const Register& r : registers_)
        if (r.name == name) return &r;
    return nullptr;
}

const Register& RegisterMap::at(std::string_view name) const {
    if (const Register* r = find(name)) return *r;
    throw std::runtime_error(source_ + ": no register named '" + std::string(name) + "'");
}

std::uint16_t RegisterMap::first_address(RegisterTable table) const {
    int first = std::numeric_limits<int>::max();
    for (const Register& r : registers_)
        if (r.table == table) first = std::min<int>(first, r.address);
    return first == std::numeric_limits<int>::max() ? 0 : std::uint16_t(first);
}

int RegisterMap::span(RegisterTable table) const {
    int end = 0;
    for (const Register& r : registers_)
        if (r.table == table) end = std::max(end, r.address + r.words());
    return end == 0 ? 0 : end - first_address(table);
}

RegisterMap load_register_map(const std::string& path) {
    const toml::table root = config::load_toml_file(path);
    std::vector<Register> registers;
    for (const auto& [key, node] : root) {
        if (key.str() != "register")
            throw std::runtime_error(path + ":" + std::to_string(node.source().begin.line) +
                                     ": unknown section [" + std::string(key.str()) +
                                     "] (expected [[register]] entries)");
        const toml::array* array = node.as_array();
        if (!array)
            throw std::runtime_error(path +
                                     ": 'register' must be an array of tables ([[register]])");
        for (const toml::node& entry : *array) {
            if (!entry.is_table())
                throw std::runtime_error(path + ":" + std::to_string(entry.source().begin.line) +
                                         ": each [[register]] must be a table");
            config::ConfigSection section(entry.as_table(), {path},
                                          "register #" + std::to_string(registers.size() + 1));
            registers.push_back(parse_register(section));
        }
    }
    return RegisterMap(std::move(registers), path);
}

}  // namespace tilejet::drivers
