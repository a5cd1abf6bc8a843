#pragma once

// The daemon's states (docs/design.md section 6). Every transition is one log line with its reason,
// so the journal tells why the line stopped.
#include <chrono>
#include <string>
#include <string_view>

namespace tilejet::daemon {

enum class LineStatus { idle, ready, printing, paused, faulted, estop };
std::string_view to_string(LineStatus status);

class LineStateMachine {
  public:
    // Logs "state A -> B: reason" when the state or the reason changes.
    void set(LineStatus status, const std::string& reason);
    LineStatus status() const { return status_; }
    const std::string& reason() const { return reason_; }

  private:
    LineStatus status_ = LineStatus::idle;
    std::string reason_ = "starting";
};

// One line on stderr (the journal under systemd), prefixed like the rest of the daemon's log.
void log_line(const std::string& message);

}  // namespace tilejet::daemon
