#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace tilejet::drivers {

// Modbus keeps read-only input registers (function 04) and read/write holding registers
// (03 to read, 06/16 to write) in two separate address spaces.
enum class RegisterTable { input, holding };

// bool and u16 take one 16-bit register; u32 takes two, high word first (the common PLC order,
// and the one libmodbus's own MODBUS_GET_INT32_FROM_INT16 assumes).
enum class RegisterType { boolean, u16, u32 };

struct Register {
    std::string name;
    RegisterTable table = RegisterTable::input;
    std::uint16_t address = 0;
    RegisterType type = RegisterType::u16;
    std::string unit;
    std::string meaning;
    std::uint32_t max = 0;  // largest value a write may carry
    // Written again after a reconnect when the controller has set it (see ModbusLineControl).
    bool retain = false;

    int words() const { return type == RegisterType::u32 ? 2 : 1; }
    bool writable() const { return table == RegisterTable::holding; }
    // "holding register 100 'speed_setpoint'": how errors name a register.
    std::string label() const;
};

// The line PLC's register map, read from one file (config/registers.toml) by both tilejet's
// Modbus client and the line simulator, so the two can never disagree.
class RegisterMap {
  public:
    explicit RegisterMap(std::vector<Register> registers, std::string source = {});

    const std::vector<Register>& registers() const { return registers_; }
    // Throws naming the map file when the register is not in the map.
    const Register& at(std::string_view name) const;
    const Register* find(std::string_view name) const;
    const std::string& source() const { return source_; }

    // First address and count of the block that covers every register of a table (the simulator
    // serves the whole block; addresses outside it answer "illegal data address").
    std::uint16_t first_address(RegisterTable table) const;
    int span(RegisterTable table) const;

  private:
    std::vector<Register> registers_;
    std::string source_;
};

// Reads and validates a register map file: unique names, no two registers sharing an address,
// every register that LineControl relies on present with the right table.
RegisterMap load_register_map(const std::string& path);

std::string_view to_string(RegisterTable table);
std::string_view to_string(RegisterType type);

}  // namespace tilejet::drivers
