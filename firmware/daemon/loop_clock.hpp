#pragma once

// LoopClock: the print loop's time. The daemon's is the steady clock; a test's is a
// VirtualLine's stepped one, so that pitch times, send deadlines, drain deadlines and speed
// changes follow the line's time, not the machine's.
#include <chrono>

namespace tilejet::daemon {

class LoopClock {
  public:
    using Clock = std::chrono::steady_clock;
    virtual ~LoopClock() = default;
    virtual Clock::time_point now() const = 0;
    // Waits (the steady clock) or moves time on (a stepped clock).
    virtual void sleep_for(Clock::duration d) = 0;

    // The steady clock, shared.
    static LoopClock& steady();
};

}  // namespace tilejet::daemon
