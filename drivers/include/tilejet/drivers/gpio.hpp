#pragma once

#include <chrono>
#include <optional>
#include <stdexcept>

#include "tilejet/drivers/config.hpp"

// Gpio: the line's digital signals as the daemon sees them, already debounced, with the e-stop
// latched. Backends (gpio_lines.hpp) only move raw levels; latched_gpio.hpp adds the logic once
// for all of them.
namespace tilejet::drivers {

// A confirmed change of an input. `timestamp` is when the raw edge happened (kernel
// CLOCK_MONOTONIC, the clock std::chrono::steady_clock reads on Linux), not when debouncing
// confirmed it: tile positions are computed from it.
struct GpioEvent {
    GpioInput input;
    bool level;  // logical level (active_low already applied): true = tile present, e-stop on
    std::chrono::nanoseconds timestamp;
};

class EstopLatched : public std::runtime_error {
    using std::runtime_error::runtime_error;
};

class Gpio {
  public:
    virtual ~Gpio() = default;

    // The next confirmed input change, or nothing when `timeout` passes first.
    virtual std::optional<GpioEvent> wait_event(std::chrono::milliseconds timeout) = 0;
    // The current debounced logical level.
    virtual bool read(GpioInput input) const = 0;
    // Throws EstopLatched when asked to enable printing while the e-stop latch is set.
    virtual void set(GpioOutput output, bool level) = 0;
    virtual bool output(GpioOutput output) const = 0;

    // Set by an e-stop edge (which also drops print-enable at once) and kept after the e-stop
    // button is released, until acknowledged.
    virtual bool estop_latched() const = 0;
    // Clears the latch; throws EstopLatched while the e-stop input is still active.
    virtual void acknowledge_estop() = 0;
};

}  // namespace tilejet::drivers
