#pragma once

#include <array>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <thread>

#include "tilejet/drivers/debouncer.hpp"
#include "tilejet/drivers/gpio.hpp"
#include "tilejet/drivers/gpio_lines.hpp"

namespace tilejet::drivers {

// The Gpio every backend is wrapped in: debounces the photo-eye and head-ready, latches the
// e-stop and drops print-enable the moment the e-stop edge arrives. A monitor thread reads the
// backend, so the e-stop reaction does not wait for the daemon to call wait_event.
// (The real safety chain is hardwired and does not depend on this; this makes sure tilejet
// never fires the heads again on its own after an e-stop.)
class LatchedGpio : public Gpio {
  public:
    LatchedGpio(std::unique_ptr<GpioLines> lines, const GpioConfig& config);
    ~LatchedGpio() override;

    std::optional<GpioEvent> wait_event(std::chrono::milliseconds timeout) override;
    bool read(GpioInput input) const override;
    void set(GpioOutput output, bool level) override;
    bool output(GpioOutput output) const override;
    bool estop_latched() const override;
    void acknowledge_estop() override;

    // Events dropped because the daemon did not collect them (queue bound reached).
    std::size_t dropped_events() const;

  private:
    void monitor();
    void on_edge(const RawEdge& edge);
    void confirm_pending(std::chrono::nanoseconds now);
    void push(GpioEvent event);
    bool logical(GpioInput input, bool physical) const;

    static constexpr std::size_t kQueueLimit = 4096;

    std::unique_ptr<GpioLines> lines_;
    GpioConfig config_;
    mutable std::mutex mutex_;
    std::condition_variable changed_;
    std::array<Debouncer, 3> debouncers_;
    std::array<bool, 3> level_{};
    std::array<bool, 2> outputs_{};
    bool estop_latched_ = false;
    std::deque<GpioEvent> queue_;
    std::size_t dropped_ = 0;
    bool stopping_ = false;
    std::thread monitor_;
};

}  // namespace tilejet::drivers
