#pragma once

#include <array>
#include <ctime>
#include <memory>
#include <mutex>

#include "tilejet/drivers/gpio_lines.hpp"

struct gpiod_chip;
struct gpiod_line;

namespace tilejet::drivers::gpiod {

// GpioLines on a real GPIO chip through libgpiod v1 (Debian 12 ships 1.6): the chip by name,
// path or number ([gpio] chip), each line by the name the device tree gives it. Inputs are
// requested for both edges, so every change arrives with the kernel's timestamp
// (CLOCK_MONOTONIC), taken in the interrupt handler rather than when tilejet reads it.
class GpiodLines : public GpioLines {
  public:
    explicit GpiodLines(const GpioConfig& config);
    ~GpiodLines() override;

    std::optional<RawEdge> wait_edge(std::chrono::microseconds timeout) override;
    bool read(GpioInput input) override;
    void write(GpioOutput output, bool level) override;

    // A kernel line event as an edge: what wait_edge returns for it. Public for the tests,
    // which have no chip to make events with.
    static RawEdge edge_from_event(GpioInput input, int event_type, const timespec& ts);

  private:
    struct ChipCloser {
        void operator()(gpiod_chip* chip) const;
    };

    std::unique_ptr<gpiod_chip, ChipCloser> chip_;
    std::string chip_name_;
    std::array<gpiod_line*, 3> inputs_{};   // owned by the chip
    std::array<gpiod_line*, 2> outputs_{};  // owned by the chip
    std::mutex write_mutex_;
};

}  // namespace tilejet::drivers::gpiod
