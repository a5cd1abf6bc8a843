#pragma once

// VirtualLine: the whole line (PLC, conveyor, photo-eye, e-stop, heads) in the caller's process,
// on a stepped clock, behind the same LineControl, Gpio and HeadSink interfaces as the real
// backends (libcamera's virtual pipeline handler is the model). Nothing runs on its own: time
// moves only when the caller advances it, or when the print loop waits for a GPIO event (the
// wait is taken as the step), so a test runs thousands of tiles, faults and restarts in
// milliseconds and the same way every time. The simulator (tilejet-linesim) and the soak still
// test the real wire; this tests the rules.
//
// The belt is linesim's Conveyor, so tiles cross the eye and the heads at the same moments as
// on the simulated line. The PLC's tile counter counts tiles reaching the heads; the heads print
// the oldest separations received before a tile's leading edge, with print-enable on, and keep a
// journal of every tile printed.

#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tilejet/drivers/config.hpp"
#include "tilejet/drivers/gpio.hpp"
#include "tilejet/drivers/head_sink.hpp"
#include "tilejet/drivers/line_control.hpp"

namespace tilejet::linesim {
class Conveyor;
struct ConveyorEvent;
}  // namespace tilejet::linesim

namespace tilejet::drivers {

class VirtualLine {
  public:
    using Clock = std::chrono::steady_clock;

    VirtualLine(const LineConfig& line, int head_buffer_tiles);
    ~VirtualLine();
    VirtualLine(const VirtualLine&) = delete;
    VirtualLine& operator=(const VirtualLine&) = delete;

    // The line's time: starts at 1000 s of the steady clock's epoch and moves only by advance.
    Clock::time_point now() const { return now_; }
    // Moves time on by `d` (the belt moves at the current speed, tiles cross the eye and the
    // heads, the counter counts).
    void advance(Clock::duration d);
    // To the next tile crossing (eye or heads) or `limit`, whichever comes first.
    void advance_to_next_crossing(Clock::time_point limit);

    // Drivers bound to this line; the line must outlive them.
    std::unique_ptr<LineControl> make_line_control();
    std::unique_ptr<Gpio> make_gpio();
    std::unique_ptr<HeadSink> make_heads();

    // --- Faults ---
    // The e-stop chain: opens (the PLC stops the conveyor, the GPIO latch drops print-enable)
    // or closes.
    void set_estop(bool open);
    void set_plc_fault(std::uint16_t code);  // 0 clears
    // A PLC that restarts: counter back to 0, conveyor stopped, run command dropped.
    void restart_plc();
    // The counter moved by `delta` without tiles (negative: back, positive: ahead).
    void shift_counter(std::int64_t delta);
    void stick_counter(bool stuck);  // the PLC counts no tile while stuck
    // Every PLC call throws LinkError while the link is down.
    void set_link(bool up);
    // The speed the PLC reports instead of the belt's (a sensor that lies); nothing: the belt's.
    void set_speed_reading(std::optional<std::uint16_t> mm_s);
    // A head controller that restarted: its buffer is gone, its journal kept.
    void restart_heads();
    // The daemon died: the GPIO side drops print-enable when its client goes (as the simulated
    // chip does, drivers/sim/PROTOCOLS.md); the PLC keeps the conveyor running.
    void daemon_gone();

    // --- What happened ---
    struct Arrival {
        std::uint64_t line_tile;
        bool printed;
        std::string job;  // the heads' name of what was printed ("job-3", "blank")
        std::uint64_t tile;
    };
    // Every tile that reached the heads, in order.
    const std::vector<Arrival>& arrivals() const { return arrivals_; }
    bool print_enable() const { return print_enable_; }
    bool conveyor_running() const { return running_; }
    double belt_speed() const;
    std::uint32_t tile_counter() const { return counter_; }
    std::size_t heads_buffered() const { return buffer_.size(); }

  private:
    class Control;
    class Lines;
    class Heads;

    void on_crossing(const linesim::ConveyorEvent& e);
    void move_belt_to(Clock::time_point t);
    void start_belt();
    void stop_belt();
    bool ready() const { return !estop_ && plc_fault_ == 0; }

    LineConfig line_;
    std::unique_ptr<linesim::Conveyor> conveyor_;
    Clock::time_point now_;

    // PLC
    bool running_ = false;
    bool estop_ = false;
    std::uint16_t plc_fault_ = 0;
    std::uint16_t setpoint_ = 0;
    std::uint32_t counter_ = 0;
    bool counter_stuck_ = false;
    bool link_up_ = true;
    std::optional<std::uint16_t> speed_reading_;

    // GPIO: levels, the e-stop latch and the events not collected yet
    bool eye_ = false;
    bool print_enable_ = false;
    bool beacon_ = false;
    bool estop_latched_ = false;
    std::deque<GpioEvent> events_;

    // Heads
    struct Queued {
        std::string job;
        std::uint64_t tile;
        Clock::time_point received;
    };
    std::size_t capacity_;
    std::deque<Queued> buffer_;
    std::vector<std::pair<std::string, std::uint64_t>> journal_;
    std::vector<Arrival> arrivals_;
};

}  // namespace tilejet::drivers
