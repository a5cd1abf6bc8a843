#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "conveyor.hpp"
#include "peer.hpp"

// The simulated GPIO chip: the inputs the line drives (photo-eye, e-stop, head-ready) and the
// outputs tilejet drives (print-enable, beacon), served on a Unix socket with the line
// protocol described in drivers/sim/PROTOCOLS.md.
namespace tilejet::linesim {

class GpioChip {
  public:
    explicit GpioChip(std::string path);
    ~GpioChip();

    std::vector<int> fds() const;
    void on_readable(int fd);

    // Changes an input and sends the edge to every client.
    void set_input(drivers::GpioInput input, bool level, ns at);
    // A raw pulse of `width` on an input, leaving its level as it was (a photo-eye glitch).
    void glitch(drivers::GpioInput input, ns at, ns width);
    bool input(drivers::GpioInput input) const { return inputs_[size_t(input)]; }
    bool output(drivers::GpioOutput output) const { return outputs_[size_t(output)]; }
    size_t clients() const { return peers_.size(); }

  private:
    void broadcast(const std::string& line);

    std::string path_;
    int listen_fd_ = -1;
    std::vector<Peer> peers_;
    std::array<bool, 3> inputs_{false, false, true};  // head-ready is up at power-on
    std::array<bool, 2> outputs_{};
};

}  // namespace tilejet::linesim
