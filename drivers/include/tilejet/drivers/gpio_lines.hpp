#pragma once

#include <chrono>
#include <optional>

#include "tilejet/drivers/config.hpp"

// GpioLines: raw access to the line's GPIO chip, the part that differs between a real chip
// (libgpiod) and the simulated one. No debouncing, no latching: that is LatchedGpio's job.
namespace tilejet::drivers {

struct RawEdge {
    GpioInput input;
    bool level;                          // physical level after the edge (active_low not applied)
    std::chrono::nanoseconds timestamp;  // CLOCK_MONOTONIC
};

class GpioLines {
  public:
    virtual ~GpioLines() = default;

    // The next edge on any input, or nothing after `timeout`. Called from one thread only.
    virtual std::optional<RawEdge> wait_edge(std::chrono::microseconds timeout) = 0;
    // Physical levels; safe to call from another thread than wait_edge's.
    virtual bool read(GpioInput input) = 0;
    virtual void write(GpioOutput output, bool level) = 0;
};

}  // namespace tilejet::drivers
