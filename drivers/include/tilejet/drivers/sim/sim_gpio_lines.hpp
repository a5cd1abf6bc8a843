#pragma once

#include <array>
#include <memory>
#include <mutex>
#include <string>

#include "tilejet/drivers/gpio_lines.hpp"

namespace tilejet::drivers::sim {

class UnixSocket;

// GpioLines on the line simulator's simulated GPIO chip, over its Unix socket ([sim]
// gpio_socket). The protocol is one text line per message (see drivers/sim/PROTOCOLS.md):
//   chip -> tilejet:  LEVEL <line> <0|1> <ns>   (once per input on connect, then READY)
//                     EDGE <line> <0|1> <ns>    (an input changed; ns = CLOCK_MONOTONIC)
//   tilejet -> chip:  SET <line> <0|1>
// Line names are the [gpio] keys: photo_eye, estop, head_ready, print_enable, beacon.
class SimGpioLines : public GpioLines {
  public:
    explicit SimGpioLines(const std::string& socket_path);
    ~SimGpioLines() override;

    std::optional<RawEdge> wait_edge(std::chrono::microseconds timeout) override;
    bool read(GpioInput input) override;
    void write(GpioOutput output, bool level) override;

  private:
    std::optional<RawEdge> parse(const std::string& line);

    std::unique_ptr<UnixSocket> socket_;
    std::mutex mutex_;
    std::array<bool, 3> levels_{};
};

}  // namespace tilejet::drivers::sim
