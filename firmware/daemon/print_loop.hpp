#pragma once

// PrintLoop: the one thread that drives the line. It keeps a mirror of what the heads hold
// (the tiles it sent, in order), pops the front each time the PLC's tile counter says a tile
// reached the heads with print-enable on, and writes every step to the job store first.
//
// Exactly once rests on three rules:
//  1. A tile is marked `sending` in the store before its bytes go out, `sent` after.
//  2. While the conveyor runs, bytes go out only in the quiet time after a tile has passed the
//     heads, and must be in before the next tile can arrive (the earliest arrival follows from
//     the tile pitch at the fastest speed). A send that ends late makes the mirror uncertain.
//  3. Whenever the mirror is uncertain (start-up after a crash, PLC link loss, a late send),
//     the loop stops the conveyor, holds print-enable low (the heads keep their buffer) and
//     RESYNCs: it sends the next tiles until the heads answer FULL, which tells how many old
//     tiles they still hold. The heads' buffer is a FIFO, so those are the newest of the tiles
//     the store says were sent; the older ones were printed.
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "controller.hpp"
#include "counter_watch.hpp"
#include "daemon_config.hpp"
#include "head_mirror.hpp"
#include "line_state.hpp"
#include "loop_clock.hpp"
#include "render_ahead.hpp"
#include "speed_governor.hpp"
#include "tilejet/drivers/gpio.hpp"
#include "tilejet/drivers/head_sink.hpp"
#include "tilejet/drivers/line_control.hpp"
#include "tilejet/jobs/job_store.hpp"

namespace tilejet::daemon {

// What a print loop runs on. The daemon's: the configured drivers, the job store at [storage]
// database, the steady clock and render threads (configured_rig). A test's: a VirtualLine's drivers
// and stepped clock, and tiles rendered in the turn that takes them, so that every run goes the
// same way.
struct LoopRig {
    // Called on the loop's own thread (libmodbus contexts belong to one thread).
    std::function<std::unique_ptr<drivers::LineControl>()> make_line;
    std::unique_ptr<drivers::Gpio> gpio;
    std::unique_ptr<drivers::HeadSink> heads;
    std::unique_ptr<jobs::JobStore> store;
    LoopClock* clock = &LoopClock::steady();
    bool render_in_turn = false;
    // With render_in_turn: each tile takes this long of the clock's time to render (0: none).
    LoopClock::Clock::duration render_time{};
};

LoopRig configured_rig(const DaemonConfig& config);

class PrintLoop {
  public:
    PrintLoop(const DaemonConfig& config, Controller& controller);
    PrintLoop(const DaemonConfig& config, Controller& controller, LoopRig rig);
    ~PrintLoop();
    // Runs until controller.terminate is set and the heads are drained (or drain_timeout):
    // start, step until it says done, finish.
    void run();
    // Makes the PLC link, on the calling thread: the thread that steps.
    void start();
    // One turn: commands, GPIO events (waits up to [print] poll for them), the PLC's state,
    // printing. False once SIGTERM's drain is over.
    bool step();
    // Print-enable low and the conveyor stopped, on the way out.
    void finish();
    // SIGHUP: the [print] speeds and timing (takes effect at the next turn).
    void reload(const PrintConfig& print);

  private:
    using Clock = LoopClock::Clock;

    void turn();
    void handle_commands();
    void handle_gpio_events(std::chrono::milliseconds wait);
    bool poll_line();
    // The fastest speed the daemon asks the conveyor for (at least 1 mm/s): what the PLC's
    // readings are judged against.
    double fastest_asked() const;
    // The counter watch latched a fault: stop the conveyor, print-enable low, resync later.
    void on_counter_fault(const std::string& why);
    void on_arrivals(const CounterWatch::Verdict& verdict, bool print_enable);
    void on_estop(std::chrono::nanoseconds at);
    void on_link_lost(const std::string& why);
    // The heads hold `count` fewer tiles than the mirror: printed uncounted, or lost.
    void on_heads_short(std::size_t count);
    bool heads_hold_mirror();
    void select_job();
    void print_turn();
    void park(const std::string& reason, LineStatus status);
    bool conveyor_stopped() const;
    bool resync();
    bool send_next(bool deadline_applies);
    enum class SendResult { sent, busy, failed };
    SendResult send(const HeadEntry& entry, const Separations& tile, bool deadline_applies);
    std::optional<Separations> tile_for(std::int64_t index, bool wait);
    void start_conveyor();
    void check_job_done();
    void end_job(jobs::JobStatus status, const std::string& message, const std::string& log);
    // An operator's stop while an e-stop or a fault holds the line: the job ends now.
    void stop_job_while_held();
    // Rendering fell behind: slower, or stopped (the governor says which).
    void adjust_speed(const std::string& reason);
    Clock::duration pitch_time() const;
    Clock::duration under_heads() const;
    Clock::time_point deadline(size_t queued) const;
    void publish();
    void set_print_enable(bool on);

    DaemonConfig config_;
    PrintConfig print_;
    std::optional<PrintConfig> reload_;
    std::mutex reload_mutex_;
    Controller& controller_;
    LoopClock& clock_;
    std::function<std::unique_ptr<drivers::LineControl>()> make_line_;
    std::unique_ptr<drivers::LineControl> line_;
    std::unique_ptr<drivers::Gpio> gpio_;
    std::unique_ptr<drivers::HeadSink> heads_;
    std::unique_ptr<jobs::JobStore> store_;
    RenderAhead render_;
    SpeedGovernor governor_;
    LineStateMachine state_;

    std::optional<jobs::Job> job_;
    std::shared_ptr<const TileRenderer> renderer_;
    HeadMirror mirror_;
    std::int64_t seq_ = 0;

    bool want_print_ = true;  // the operator's resume/pause
    bool stop_job_ = false;   // the operator's stop: cancel the job once its tiles are out
    bool link_up_ = false;
    drivers::LineState line_state_;
    bool enabled_at_poll_ = false;  // print-enable when the last poll read the counter
    // The PLC's tile counter as far as it can be believed; a fault it latched keeps the line
    // stopped until the operator acknowledges.
    CounterWatch counter_;
    Clock::time_point earliest_next_{};  // the next tile cannot reach the heads before this
    bool run_commanded_ = false;

    struct Printed {
        HeadEntry entry;
        Clock::time_point arrived_after;
    };
    std::optional<Printed> last_printed_;
    std::int64_t line_printed_ = 0, line_missed_ = 0, blanks_ = 0, spoiled_ = 0;
    bool draining_ = false;
    Clock::time_point drain_deadline_{};
    bool done_ = false;
    std::string last_error_;
    Clock::time_point next_job_check_{};
};

}  // namespace tilejet::daemon
