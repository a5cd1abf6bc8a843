#include "loop_clock.hpp"

#include <thread>

namespace tilejet::daemon {

namespace {

class SteadyClock : public LoopClock {
  public:
    Clock::time_point now() const override { return Clock::now(); }
    void sleep_for(Clock::duration d) override { std::this_thread::sleep_for(d); }
};

}  // namespace

LoopClock& LoopClock::steady() {
    static SteadyClock clock;
    return clock;
}

}  // namespace tilejet::daemon
