#pragma once

// SpeedGovernor: the speed the daemon asks the conveyor for while printing. A tile that passes
// the heads with nothing rendered for it slows the conveyor to 7/10, down to [print]
// min_speed_mm_s; at that speed the next one stops it until half the render-ahead queue is
// ready. A full queue brings the speed back up a quarter at a time, at most every 2 s, to
// [print] speed_mm_s. Pure: the print loop passes the time and does what it answers.
#include <chrono>
#include <string>

#include "daemon_config.hpp"

namespace tilejet::daemon {

class SpeedGovernor {
  public:
    using Clock = std::chrono::steady_clock;
    explicit SpeedGovernor(const PrintConfig& print) : print_(print), speed_(print.speed_mm_s) {}

    // [print] reloaded. A lower top speed applies at once (true: the speed asked for came
    // down); a higher one is reached step by step while rendering keeps up.
    bool reload(const PrintConfig& print);

    int speed() const { return speed_; }
    // The fastest speed asked for, at least 1 mm/s: what the PLC's readings are judged against.
    double fastest_asked() const;
    // Why the conveyor is slower than the set speed or stopped; empty at full speed.
    const std::string& reason() const { return reason_; }
    bool stopped_for_render() const { return stopped_; }

    enum class Change { none, slower, stop };
    // A tile passed the heads with nothing rendered for it.
    Change render_behind(const std::string& reason, Clock::time_point now);
    // Tiles that must be ready before a conveyor stopped for rendering starts again: half the
    // queue, or what is left of the job if that is less.
    static int ready_to_restart(int capacity, int wanted);
    // The conveyor stopped for rendering may start again.
    void restarting() { stopped_ = false; }
    // Render-ahead is full: true when the speed went up.
    bool render_full(Clock::time_point now);

  private:
    PrintConfig print_;
    int speed_;
    bool stopped_ = false;
    std::string reason_;
    Clock::time_point last_change_{};
};

}  // namespace tilejet::daemon
