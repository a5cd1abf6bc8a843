#pragma once

// What stops or slows the line, in the words an operator at the panel needs: what happened
// and what to do about it. One entry per condition; empty when the line is fine.
#include <nlohmann/json.hpp>

#include "controller.hpp"

namespace tilejet::daemon {

// [{"code", "title", "action", "severity": "stop" | "warning"}]
nlohmann::json line_faults(const LineSnapshot& s);

}  // namespace tilejet::daemon
