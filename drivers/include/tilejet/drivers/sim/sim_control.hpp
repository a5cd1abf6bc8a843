#pragma once

#include <chrono>
#include <string>

// The line simulator's control socket ([sim] control_socket): fault injection and inspection.
// One request line, one reply line of JSON ({"ok":true,...} or {"ok":false,"error":"..."}).
// Requests: estop on|off, fault CODE|clear, drop-link SECONDS, delay MS, glitch [US],
// stop-conveyor, start-conveyor, set REGISTER VALUE, status.
namespace tilejet::drivers::sim {

class SimControl {
  public:
    explicit SimControl(std::string socket_path,
                        std::chrono::milliseconds timeout = std::chrono::milliseconds(2000));

    // Sends one request; returns the JSON reply, throws with the simulator's error if not ok.
    std::string request(const std::string& line);

  private:
    std::string path_;
    std::chrono::milliseconds timeout_;
};

}  // namespace tilejet::drivers::sim
