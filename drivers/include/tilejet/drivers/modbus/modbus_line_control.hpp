#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "tilejet/drivers/config.hpp"
#include "tilejet/drivers/line_control.hpp"
#include "tilejet/drivers/register_map.hpp"

typedef struct _modbus modbus_t;  // libmodbus's opaque context

namespace tilejet::drivers {

// LineControl over Modbus TCP or RTU (libmodbus), for the line PLC and for the simulator alike.
//
// - Every call is bounded by [modbus] response_timeout_ms (also used as the byte timeout, and
//   by libmodbus as the TCP connect timeout).
// - On a timeout, a reset or broken link (ECONNRESET, EPIPE, ...) or a reply that makes no sense,
//   the context is thrown away and the next call opens a fresh one. libmodbus 3.1.6 (Debian 12)
//   does not recover a dropped TCP link with its own error-recovery flags (upstream #734, #735),
//   and after a timeout a late reply would be taken as the answer to the next request; a fresh
//   context avoids both.
// - Reconnect attempts back off from reconnect_min_ms, doubling up to reconnect_max_ms; between
//   attempts calls fail at once with LinkError instead of blocking the caller.
// - After each reconnect, the state is re-synced: every register is read again, and retained
//   registers (config/registers.toml `retain`) get the controller's last value written back.
//   Writes made while the link is down are not queued: they fail with LinkError, and only the
//   last value of each retained register is kept (one slot per register, bounded).
// - A libmodbus context must not be shared between threads: an object belongs to the thread
//   that made it and refuses calls from any other (make one per thread).
class ModbusLineControl : public LineControl {
  public:
    ModbusLineControl(const ModbusConfig& config, RegisterMap registers);
    ~ModbusLineControl() override;
    ModbusLineControl(const ModbusLineControl&) = delete;
    ModbusLineControl& operator=(const ModbusLineControl&) = delete;

    LineState read_state() override;
    void set_speed(std::uint16_t mm_s) override;
    void run() override;
    void stop() override;
    bool connected() const override;

    // One register by its name in the map (u32 values span two registers).
    std::uint32_t read(const std::string& name);
    void write(const std::string& name, std::uint32_t value);
    // Every register, by name, in one block read per table.
    std::map<std::string, std::uint32_t> read_all();

    // How many times the link was (re-)established and synced, the first connect included.
    std::size_t resyncs() const { return resyncs_; }
    // "tcp 127.0.0.1:1502" or "rtu /dev/ttyUSB0".
    const std::string& endpoint() const { return endpoint_; }
    const RegisterMap& registers() const { return registers_; }

  private:
    struct ContextDeleter {
        void operator()(modbus_t* ctx) const;
    };
    using Context = std::unique_ptr<modbus_t, ContextDeleter>;
    using Clock = std::chrono::steady_clock;

    modbus_t* context();
    Context open_context() const;
    void resync();
    [[noreturn]] void fail(const std::string& what, int error);
    void check_thread() const;
    std::vector<std::uint16_t> read_block(RegisterTable table, const std::string& what);
    void write_register(const Register& reg, std::uint32_t value);
    std::map<std::string, std::uint32_t> decode(RegisterTable table,
                                                const std::vector<std::uint16_t>& words) const;

    ModbusConfig config_;
    RegisterMap registers_;
    std::string endpoint_;
    std::thread::id owner_;
    Context ctx_;
    Clock::time_point next_attempt_{};
    std::chrono::milliseconds backoff_;
    std::map<std::string, std::uint32_t> retained_;
    std::size_t resyncs_ = 0;
};

}  // namespace tilejet::drivers
