#include "tilejet/drivers/latched_gpio.hpp"

#include <cstdio>
#include <exception>

namespace tilejet::drivers {

namespace {

using std::chrono::nanoseconds;

nanoseconds monotonic_now() {
    return std::chrono::duration_cast<nanoseconds>(
        std::chrono::steady_clock::now().time_since_epoch());
}

size_t index(GpioInput input) {
    return size_t(input);
}
size_t index(GpioOutput output) {
    return size_t(output);
}

}  // namespace

LatchedGpio::LatchedGpio(std::unique_ptr<GpioLines> lines, const GpioConfig& config)
    : lines_(std::move(lines)),
      config_(config),
      debouncers_{Debouncer(false, config.debounce), Debouncer(false, config.debounce),
                  Debouncer(false, config.debounce)} {
    // Outputs start in the safe state whatever the chip held before.
    for (GpioOutput o : kGpioOutputs)
        lines_->write(o, false);
    for (GpioInput i : kGpioInputs) {
        level_[index(i)] = logical(i, lines_->read(i));
        debouncers_[index(i)] = Debouncer(level_[index(i)], config.debounce);
    }
    // Starting with the e-stop pressed needs an acknowledgement like any other e-stop.
    estop_latched_ = level_[index(GpioInput::estop)];
    monitor_ = std::thread([this] { monitor(); });
}

LatchedGpio::~LatchedGpio() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    monitor_.join();
}

bool LatchedGpio::logical(GpioInput input, bool physical) const {
    return physical != config_.input_active_low[index(input)];
}

void LatchedGpio::monitor() {
    // The wait is short so that the destructor never waits long for this thread.
    constexpr std::chrono::microseconds kPoll{20000};
    while (true) {
        std::chrono::microseconds wait = kPoll;
        {
            std::lock_guard lock(mutex_);
            if (stopping_) return;
            for (const Debouncer& d : debouncers_)
                if (auto deadline = d.deadline()) {
                    auto left = std::chrono::duration_cast<std::chrono::microseconds>(
                        *deadline - monotonic_now());
                    wait = std::max(std::chrono::microseconds(0), std::min(wait, left));
                }
        }
        std::optional<RawEdge> edge;
        try {
            edge = lines_->wait_edge(wait);
        } catch (const std::exception& e) {
            // A backend that lost its chip cannot recover here; say so once and stop reporting.
            std::fprintf(stderr, "tilejet: gpio: %s\n", e.what());
            std::lock_guard lock(mutex_);
            stopping_ = true;
            changed_.notify_all();
            return;
        }
        std::lock_guard lock(mutex_);
        // Confirm by the clock only when no edge is waiting: an edge already queued (in the
        // kernel or the socket) may be the one that cancels a glitch, however late it is read.
        if (edge) {
            confirm_pending(edge->timestamp);
            on_edge(*edge);
        } else {
            confirm_pending(monotonic_now());
        }
    }
}

void LatchedGpio::on_edge(const RawEdge& edge) {
    const bool level = logical(edge.input, edge.level);
    if (edge.input == GpioInput::estop) {
        // Never debounced: the first sign of an e-stop acts.
        if (level == level_[index(GpioInput::estop)]) return;
        level_[index(GpioInput::estop)] = level;
        if (level) {
            estop_latched_ = true;
            outputs_[index(GpioOutput::print_enable)] = false;
            lines_->write(GpioOutput::print_enable, false);
        }
        push({GpioInput::estop, level, edge.timestamp});
        return;
    }
    debouncers_[index(edge.input)].edge(level, edge.timestamp);
}

void LatchedGpio::confirm_pending(nanoseconds now) {
    for (GpioInput i : {GpioInput::photo_eye, GpioInput::head_ready})
        if (auto confirmed = debouncers_[index(i)].confirm(now)) {
            level_[index(i)] = confirmed->first;
            push({i, confirmed->first, confirmed->second});
        }
}

void LatchedGpio::push(GpioEvent event) {
    if (queue_.size() >= kQueueLimit) {
        queue_.pop_front();
        ++dropped_;
    }
    queue_.push_back(event);
    changed_.notify_all();
}

std::optional<GpioEvent> LatchedGpio::wait_event(std::chrono::milliseconds timeout) {
    std::unique_lock lock(mutex_);
    changed_.wait_for(lock, timeout, [this] { return !queue_.empty() || stopping_; });
    if (queue_.empty()) return std::nullopt;
    GpioEvent e = queue_.front();
    queue_.pop_front();
    return e;
}

bool LatchedGpio::read(GpioInput input) const {
    std::lock_guard lock(mutex_);
    return level_[index(input)];
}

void LatchedGpio::set(GpioOutput output, bool level) {
    std::lock_guard lock(mutex_);
    if (output == GpioOutput::print_enable && level && estop_latched_)
        throw EstopLatched("print-enable refused: the e-stop is latched (acknowledge it first)");
    lines_->write(output, level);
    outputs_[index(output)] = level;
}

bool LatchedGpio::output(GpioOutput output) const {
    std::lock_guard lock(mutex_);
    return outputs_[index(output)];
}

bool LatchedGpio::estop_latched() const {
    std::lock_guard lock(mutex_);
    return estop_latched_;
}

void LatchedGpio::acknowledge_estop() {
    std::lock_guard lock(mutex_);
    if (level_[index(GpioInput::estop)])
        throw EstopLatched("e-stop cannot be acknowledged while it is still pressed");
    estop_latched_ = false;
}

std::size_t LatchedGpio::dropped_events() const {
    std::lock_guard lock(mutex_);
    return dropped_;
}

}  // namespace tilejet::drivers
