#pragma once

// Controller: what the API (and signals) share with the print loop: operator commands in, a
// status snapshot out. The print loop owns the line; nobody else touches the drivers.
#include <atomic>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "line_state.hpp"

namespace tilejet::daemon {

enum class Command { pause, resume, stop_job, acknowledge };

struct LineSnapshot {
    LineStatus status = LineStatus::idle;
    std::string reason = "starting";
    std::optional<std::int64_t> job;
    bool link_up = false;
    bool estop_latched = false;
    bool conveyor_running = false;
    int speed_setpoint_mm_s = 0;
    int speed_mm_s = 0;                // measured by the PLC
    std::uint16_t plc_fault_code = 0;  // the PLC's active fault; 0 = none
    bool counter_fault = false;        // the PLC's tile counter went back or jumped ahead
    std::uint32_t tile_counter = 0;
    int heads_queue = 0;     // tiles the heads hold (as the daemon tracks them)
    int rendered_ahead = 0;  // tiles ready in the render-ahead queue
    std::int64_t line_tiles_printed = 0, line_tiles_missed = 0, blanks = 0;
    std::int64_t spoiled = 0;
};

class Controller {
  public:
    void post(Command command) {
        std::lock_guard lock(mutex_);
        commands_.push_back(command);
    }
    std::vector<Command> take_commands() {
        std::lock_guard lock(mutex_);
        return std::exchange(commands_, {});
    }
    void publish(const LineSnapshot& snapshot) {
        std::lock_guard lock(mutex_);
        snapshot_ = snapshot;
    }
    LineSnapshot snapshot() const {
        std::lock_guard lock(mutex_);
        return snapshot_;
    }

    std::atomic<bool> terminate{false};         // SIGTERM: finish the tiles in the heads, then stop
    std::atomic<std::int64_t> heartbeat_ns{0};  // the print loop's last turn (watchdog)

  private:
    mutable std::mutex mutex_;
    std::vector<Command> commands_;
    LineSnapshot snapshot_;
};

}  // namespace tilejet::daemon
