#pragma once

// systemd's notify protocol (Type=notify): READY, STATUS, WATCHDOG, STOPPING. Without systemd
// (NOTIFY_SOCKET unset) every call does nothing.
#include <chrono>
#include <optional>
#include <string>

namespace tilejet::daemon {

void notify_ready(const std::string& status);
void notify_status(const std::string& status);
void notify_watchdog();
void notify_stopping();
// Half the unit's WatchdogSec, when the watchdog is on.
std::optional<std::chrono::microseconds> watchdog_interval();

}  // namespace tilejet::daemon
