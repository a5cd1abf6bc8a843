#include "line_state.hpp"

#include <cstdio>

namespace tilejet::daemon {

std::string_view to_string(LineStatus status) {
    switch (status) {
        case LineStatus::idle:
            return "idle";
        case LineStatus::ready:
            return "ready";
        case LineStatus::printing:
            return "printing";
        case LineStatus::paused:
            return "paused";
        case LineStatus::faulted:
            return "faulted";
        case LineStatus::estop:
            return "e-stop";
    }
    return "?";
}

void LineStateMachine::set(LineStatus status, const std::string& reason) {
    if (status == status_ && reason == reason_) return;
    log_line("state " + std::string(to_string(status_)) + " -> " + std::string(to_string(status)) +
             ": " + reason);
    status_ = status;
    reason_ = reason;
}

void log_line(const std::string& message) {
    std::fprintf(stderr, "tilejetd: %s\n", message.c_str());
    std::fflush(stderr);
}

}  // namespace tilejet::daemon
