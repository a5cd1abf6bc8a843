#include "line_state.hpp"

#include <cstdio>

#include "tilejet/config/enum_names.hpp"

namespace tilejet::daemon {

namespace {

constexpr config::EnumNames kLineStatus{std::array<std::pair<LineStatus, std::string_view>, 6>{{
    {LineStatus::idle, "idle"},
    {LineStatus::ready, "ready"},
    {LineStatus::printing, "printing"},
    {LineStatus::paused, "paused"},
    {LineStatus::faulted, "faulted"},
    {LineStatus::estop, "e-stop"},
}}};

}  // namespace

std::string_view to_string(LineStatus status) {
    return kLineStatus.name(status);
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
