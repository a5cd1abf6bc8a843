#include "counter_watch.hpp"

#include <algorithm>
#include <cmath>

namespace tilejet::daemon {

namespace {

double seconds(CounterWatch::Clock::duration d) {
    return std::chrono::duration<double>(d).count();
}

}  // namespace

CounterWatch::Verdict CounterWatch::judge(const Reading& reading, double fastest_asked) {
    Verdict verdict;
    last_took_ = reading.took;
    if (fault_) return verdict;  // nothing is counted until the operator acknowledges
    if (auto why = implausible_speed(reading.speed_mm_s, fastest_asked)) {
        fault_ = verdict.fault = std::move(why);
        return verdict;
    }
    if (!known_) {
        known_ = true;
        counter_ = reading.tile_counter;
        eye_lead_ = 0;  // the eye and the counter start even
        previous_ = reading.started;
        return verdict;
    }
    if (reading.tile_counter != counter_) {
        if (auto why = implausible_arrivals(reading.tile_counter, reading.started - previous_,
                                            fastest_asked)) {
            // Nothing is counted: which tiles passed, and with what ink, is unknown.
            fault_ = verdict.fault = std::move(why);
            return verdict;
        }
        const std::uint32_t arrived = reading.tile_counter - counter_;  // wraps at 2^32
        verdict.arrived = arrived;
        verdict.first_line_tile = counter_;
        verdict.since = previous_;
        counter_ = reading.tile_counter;
        // A tile already between the eye and the heads when counting began was never seen.
        eye_lead_ = std::max<std::int64_t>(0, eye_lead_ - std::int64_t(arrived));
    }
    if (auto why = stuck(fastest_asked)) {
        fault_ = verdict.fault = std::move(why);
        return verdict;
    }
    previous_ = reading.started;
    return verdict;
}

void CounterWatch::photo_eye(bool level, std::chrono::nanoseconds at, double fastest_asked) {
    if (level) {
        eye_on_since_ = at;
        return;
    }
    if (!eye_on_since_) return;
    const double shortest_s = 0.5 * line_.tile_length_mm / (1.5 * std::max(1.0, fastest_asked));
    if (std::chrono::duration<double>(at - *eye_on_since_).count() >= shortest_s) ++eye_lead_;
    eye_on_since_.reset();
}

std::optional<std::string> CounterWatch::implausible_speed(double speed,
                                                           double fastest_asked) const {
    // Half again the fastest speed the daemon ever asks for, and some slack for a conveyor that
    // overshoots when it starts; the PLC's own setpoint is a reading too, so it does not count.
    const double limit = 1.5 * fastest_asked + 50;
    if (std::isfinite(speed) && speed >= 0 && speed <= limit) return std::nullopt;
    return "PLC speed reading " + std::to_string(speed) +
           " mm/s is beyond anything the line was asked for (at most " +
           std::to_string(int(fastest_asked)) + " mm/s)";
}

std::optional<std::string> CounterWatch::implausible_arrivals(std::uint32_t now,
                                                              Clock::duration elapsed,
                                                              double fastest_asked) const {
    // A counter that went back by less than half its range went back; one that went on by more
    // than that is judged as a jump below (2^31 tiles cannot pass between two reads anyway).
    if (now < counter_ && counter_ - now < (1u << 31))
        return "PLC tile counter went back from " + std::to_string(counter_) + " to " +
               std::to_string(now) + " (PLC restart?)";
    // At most one tile a pitch at half again the fastest speed the daemon runs the line, and
    // two for the tile already under the eye when the last read began.
    const double fastest = 1.5 * std::max(1.0, fastest_asked);
    const double pitch_s = std::max(1.0, line_.tile_pitch_mm) / fastest;
    const double possible = std::max(0.0, seconds(elapsed)) / pitch_s + 2;
    const std::uint32_t arrived = now - counter_;  // wraps at 2^32
    if (double(arrived) <= possible) return std::nullopt;
    return "PLC tile counter jumped from " + std::to_string(counter_) + " to " +
           std::to_string(now) + ": " + std::to_string(arrived) + " tiles in " +
           std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(elapsed).count()) +
           " ms, at most " + std::to_string(std::uint64_t(possible)) + " can have passed";
}

std::optional<std::string> CounterWatch::stuck(double fastest_asked) const {
    // The tiles that fit between the eye and the heads, one more for the tile at each, and two
    // for the moments between the eye's edge and the counter's read.
    const std::int64_t on_the_way =
        std::int64_t(std::ceil(std::max(0.0, line_.heads_mm - line_.photo_eye_mm) /
                               std::max(1.0, line_.tile_pitch_mm))) +
        1;
    // A slow read (a PLC answering late, within the timeout) gives a counter older than the
    // eye's edges by as long as it took: the tiles that can pass meanwhile are allowed too (the
    // soak's delayed replies once stopped the line for a counter that was only late).
    const double late_tiles =
        seconds(last_took_) * std::max(1.0, fastest_asked) / std::max(1.0, line_.tile_pitch_mm);
    const std::int64_t allowed = on_the_way + 2 + std::lround(late_tiles);  // a quick read: 0
    if (eye_lead_ <= allowed) return std::nullopt;
    return "PLC tile counter stuck at " + std::to_string(counter_) + ": the photo-eye saw " +
           std::to_string(eye_lead_) + " tiles pass that it did not count (at most " +
           std::to_string(allowed) + " can be on their way to the heads)";
}

}  // namespace tilejet::daemon
