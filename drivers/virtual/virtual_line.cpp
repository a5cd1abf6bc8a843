#include "tilejet/drivers/virtual_line.hpp"

#include <algorithm>
#include <cmath>

#include "../sim/linesim/conveyor.hpp"

namespace tilejet::drivers {

using linesim::ConveyorEvent;
using namespace std::chrono_literals;

namespace {

std::chrono::nanoseconds since_epoch(VirtualLine::Clock::time_point t) {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch());
}

}  // namespace

// The PLC's side: what ModbusLineControl reads and writes, without the wire.
class VirtualLine::Control : public LineControl {
  public:
    explicit Control(VirtualLine& line) : line_(line) {}

    LineState read_state() override {
        check_link();
        LineState s;
        s.ready = line_.ready();
        s.running = line_.running_;
        s.estop = line_.estop_;
        s.fault_code = line_.plc_fault_;
        s.speed_mm_s = line_.speed_reading_ ? *line_.speed_reading_
                                            : std::uint16_t(std::lround(line_.belt_speed()));
        s.speed_setpoint_mm_s = line_.setpoint_;
        s.run_commanded = line_.running_;
        s.tile_counter = line_.counter_;
        return s;
    }
    void set_speed(std::uint16_t mm_s) override {
        check_link();
        line_.move_belt_to(line_.now_);
        line_.setpoint_ = mm_s;
        if (line_.running_) line_.conveyor_->set_speed(mm_s);
    }
    void run() override {
        check_link();
        if (line_.ready()) line_.start_belt();  // refused while not ready, as the PLC does
    }
    void stop() override {
        check_link();
        line_.stop_belt();
    }
    bool connected() const override { return line_.link_up_; }

  private:
    void check_link() const {
        if (!line_.link_up_) throw LinkError("virtual PLC: link down");
    }
    VirtualLine& line_;
};

// The GPIO as LatchedGpio presents it: already debounced, the e-stop latched. Waiting for an
// event is what moves the line's time.
class VirtualLine::Lines : public Gpio {
  public:
    explicit Lines(VirtualLine& line) : line_(line) {}

    std::optional<GpioEvent> wait_event(std::chrono::milliseconds timeout) override {
        const Clock::time_point until = line_.now_ + timeout;
        while (line_.events_.empty() && line_.now_ < until)
            line_.advance_to_next_crossing(until);
        if (line_.events_.empty()) return std::nullopt;
        const GpioEvent e = line_.events_.front();
        line_.events_.pop_front();
        return e;
    }
    bool read(GpioInput input) const override {
        switch (input) {
            case GpioInput::photo_eye:
                return line_.eye_;
            case GpioInput::estop:
                return line_.estop_;
            case GpioInput::head_ready:
                return true;
        }
        return false;
    }
    void set(GpioOutput output, bool level) override {
        if (output == GpioOutput::beacon) {
            line_.beacon_ = level;
            return;
        }
        if (level && line_.estop_latched_)
            throw EstopLatched("print-enable refused: the e-stop is latched");
        line_.print_enable_ = level;
    }
    bool output(GpioOutput output) const override {
        return output == GpioOutput::beacon ? line_.beacon_ : line_.print_enable_;
    }
    bool estop_latched() const override { return line_.estop_latched_; }
    void acknowledge_estop() override {
        if (line_.estop_) throw EstopLatched("the e-stop is still pressed");
        line_.estop_latched_ = false;
    }

  private:
    VirtualLine& line_;
};

// Heads with a FIFO buffer and a print journal; a send takes no time.
class VirtualLine::Heads : public HeadSink {
  public:
    explicit Heads(VirtualLine& line) : line_(line) {}

    int send(const TileSeparations& tile, std::chrono::milliseconds) override {
        if (line_.buffer_.size() >= line_.capacity_) throw HeadsBusy("virtual heads: FULL");
        line_.buffer_.push_back({tile.job_id, tile.tile_index, line_.now_});
        return int(line_.buffer_.size());
    }
    int held(std::chrono::milliseconds) override { return int(line_.buffer_.size()); }
    std::optional<bool> printed(const std::string& job_id, std::uint64_t tile_index,
                                std::chrono::milliseconds) override {
        return std::find(line_.journal_.begin(), line_.journal_.end(),
                         std::pair{job_id, tile_index}) != line_.journal_.end();
    }

  private:
    VirtualLine& line_;
};

VirtualLine::VirtualLine(const LineConfig& line, int head_buffer_tiles)
    : line_(line),
      conveyor_(std::make_unique<linesim::Conveyor>(line)),
      now_(Clock::time_point(1000s)),
      capacity_(std::size_t(std::max(1, head_buffer_tiles))) {
    conveyor_->advance(since_epoch(now_), [](const ConveyorEvent&) {});
}

VirtualLine::~VirtualLine() = default;

std::unique_ptr<LineControl> VirtualLine::make_line_control() {
    return std::make_unique<Control>(*this);
}
std::unique_ptr<Gpio> VirtualLine::make_gpio() {
    return std::make_unique<Lines>(*this);
}
std::unique_ptr<HeadSink> VirtualLine::make_heads() {
    return std::make_unique<Heads>(*this);
}

double VirtualLine::belt_speed() const {
    return conveyor_->speed();
}

void VirtualLine::advance(Clock::duration d) {
    move_belt_to(now_ + d);
}

void VirtualLine::advance_to_next_crossing(Clock::time_point limit) {
    const auto next = conveyor_->next_event(since_epoch(now_));
    const Clock::time_point to =
        next
            ? std::min(limit, Clock::time_point(std::chrono::duration_cast<Clock::duration>(*next)))
            : limit;
    move_belt_to(std::max(to, now_));
}

void VirtualLine::move_belt_to(Clock::time_point t) {
    conveyor_->advance(since_epoch(t), [this](const ConveyorEvent& e) { on_crossing(e); });
    now_ = std::max(now_, t);
}

void VirtualLine::on_crossing(const ConveyorEvent& e) {
    switch (e.kind) {
        case ConveyorEvent::eye_on:
        case ConveyorEvent::eye_off:
            eye_ = e.kind == ConveyorEvent::eye_on;
            events_.push_back({GpioInput::photo_eye, eye_, e.time});
            break;
        case ConveyorEvent::at_heads: {
            const Clock::time_point at{std::chrono::duration_cast<Clock::duration>(e.time)};
            const bool have = !buffer_.empty() && buffer_.front().received <= at;
            if (have && print_enable_) {
                const Queued q = buffer_.front();
                buffer_.pop_front();
                journal_.emplace_back(q.job, q.tile);
                arrivals_.push_back({e.tile, true, q.job, q.tile});
            } else {
                arrivals_.push_back({e.tile, false, {}, 0});
            }
            if (!counter_stuck_) ++counter_;
            break;
        }
    }
}

void VirtualLine::start_belt() {
    move_belt_to(now_);
    running_ = true;
    conveyor_->set_speed(setpoint_);
}

void VirtualLine::stop_belt() {
    move_belt_to(now_);
    running_ = false;
    conveyor_->set_speed(0);
}

void VirtualLine::set_estop(bool open) {
    if (open == estop_) return;
    estop_ = open;
    if (open) {
        stop_belt();
        // LatchedGpio's reaction: latch, and print-enable low at once.
        estop_latched_ = true;
        print_enable_ = false;
    }
    events_.push_back({GpioInput::estop, open, since_epoch(now_)});
}

void VirtualLine::set_plc_fault(std::uint16_t code) {
    plc_fault_ = code;
    if (code != 0) stop_belt();
}

void VirtualLine::restart_plc() {
    stop_belt();
    counter_ = 0;
    setpoint_ = 0;
}

void VirtualLine::shift_counter(std::int64_t delta) {
    counter_ = std::uint32_t(std::int64_t(counter_) + delta);
}

void VirtualLine::stick_counter(bool stuck) {
    counter_stuck_ = stuck;
}

void VirtualLine::set_link(bool up) {
    link_up_ = up;
}

void VirtualLine::set_speed_reading(std::optional<std::uint16_t> mm_s) {
    speed_reading_ = mm_s;
}

void VirtualLine::restart_heads() {
    buffer_.clear();
}

void VirtualLine::daemon_gone() {
    print_enable_ = false;
    events_.clear();
}

}  // namespace tilejet::drivers
