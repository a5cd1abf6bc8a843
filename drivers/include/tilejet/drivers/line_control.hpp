#pragma once

#include <cstdint>
#include <stdexcept>

// LineControl: what the daemon asks of the line's PLC. The real one talks Modbus
// (modbus/modbus_line_control.hpp); against the simulator it is the same class, because the
// simulator is a real Modbus server.
namespace tilejet::drivers {

struct LineState {
    bool ready = false;    // the line can run
    bool running = false;  // the conveyor moves
    bool estop = false;    // the PLC sees the e-stop chain open
    std::uint16_t fault_code = 0;
    std::uint16_t speed_mm_s = 0;           // measured
    std::uint16_t speed_setpoint_mm_s = 0;  // asked for
    bool run_commanded = false;
    std::uint32_t tile_counter = 0;
};

// The link to the PLC is down (timeout, reset, refused, or a reply that made no sense). The
// client reconnects by itself; the caller decides whether to retry, pause or fault.
class LinkError : public std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The PLC answered, with a Modbus exception (illegal address, illegal value, busy, ...), or a
// value could not be sent (out of the register's range). The link is fine.
class RegisterError : public std::runtime_error {
    using std::runtime_error::runtime_error;
};

class LineControl {
  public:
    virtual ~LineControl() = default;

    // Reads every status register in one go.
    virtual LineState read_state() = 0;
    virtual void set_speed(std::uint16_t mm_s) = 0;
    virtual void run() = 0;
    virtual void stop() = 0;
    // False while the link is down and waiting for the next reconnect attempt.
    virtual bool connected() const = 0;
};

}  // namespace tilejet::drivers
