#include "speed_governor.hpp"

#include <algorithm>

namespace tilejet::daemon {

namespace {
// Speeding up sooner than this after a change would undo a slow-down before the queue shows
// whether rendering keeps up at the lower speed.
constexpr auto kSpeedUpAfter = std::chrono::seconds(2);
}  // namespace

bool SpeedGovernor::reload(const PrintConfig& print) {
    print_ = print;
    if (speed_ <= print_.speed_mm_s) return false;
    speed_ = print_.speed_mm_s;
    return true;
}

double SpeedGovernor::fastest_asked() const {
    return std::max<double>({double(print_.speed_mm_s), double(speed_), 1.0});
}

SpeedGovernor::Change SpeedGovernor::render_behind(const std::string& reason,
                                                   Clock::time_point now) {
    reason_ = reason;
    if (speed_ > print_.min_speed_mm_s) {
        speed_ = std::max(print_.min_speed_mm_s, speed_ * 7 / 10);
        last_change_ = now;
        return Change::slower;
    }
    if (stopped_) return Change::none;
    stopped_ = true;
    return Change::stop;
}

int SpeedGovernor::ready_to_restart(int capacity, int wanted) {
    return std::min(std::max(1, capacity / 2), wanted);
}

bool SpeedGovernor::render_full(Clock::time_point now) {
    if (speed_ >= print_.speed_mm_s || now - last_change_ <= kSpeedUpAfter) return false;
    speed_ = std::min(print_.speed_mm_s, speed_ + std::max(1, speed_ / 4));
    last_change_ = now;
    if (speed_ == print_.speed_mm_s) reason_.clear();
    return true;
}

}  // namespace tilejet::daemon
