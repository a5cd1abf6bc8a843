#pragma once

// CounterWatch: whether the PLC's tile counter can be believed. The counter counts tiles that
// reached the heads since the PLC's power-up; the print loop pops one tile off the head mirror
// per count, so a counter that goes back (a PLC restart), jumps further than tiles can travel,
// sticks while the photo-eye sees tiles pass, or comes with a speed reading beyond anything the
// line was asked for would mark tiles printed that were not, or walk billions of false
// arrivals. Every reading is judged here before a single tile is counted; a fault is latched
// until the operator acknowledges, and counting then starts afresh from the next reading.
// Pure and clock-free: the loop passes the times of its reads and the photo-eye's edges.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include "tilejet/drivers/config.hpp"

namespace tilejet::daemon {

class CounterWatch {
  public:
    using Clock = std::chrono::steady_clock;
    explicit CounterWatch(const drivers::LineConfig& line) : line_(line) {}

    struct Reading {
        std::uint32_t tile_counter = 0;
        double speed_mm_s = 0;        // measured
        Clock::time_point started{};  // when the read was sent
        Clock::duration took{};       // how long the PLC took to answer
    };
    struct Verdict {
        std::uint32_t arrived = 0;          // tiles that reached the heads since the last reading
        std::uint32_t first_line_tile = 0;  // the counter value of the first of them
        Clock::time_point since{};          // the last of them came after this (the previous read)
        std::optional<std::string> fault;   // set: nothing is counted, the line must stop
    };
    // Judges a reading; `fastest_asked` is the fastest speed the daemon asks for (mm/s).
    // Arrivals are counted (and the counter moves on) only when the verdict has no fault.
    Verdict judge(const Reading& reading, double fastest_asked);

    // The photo-eye's edges: a pulse as long as a tile takes to pass, at half again the fastest
    // speed and more, is a tile (shorter ones are glitches).
    void photo_eye(bool level, std::chrono::nanoseconds at, double fastest_asked);

    const std::optional<std::string>& latched_fault() const { return fault_; }
    // The operator acknowledged the fault: count from the next reading on.
    void acknowledge() { fault_.reset(), known_ = false; }
    // The link was lost: what passed meanwhile is unknown; count from the next reading on.
    void forget() { known_ = false; }
    // The heads' journal shows `tiles` printed that the counter never counted (stuck for a
    // moment): they passed the photo-eye too, so the eye's lead no longer includes them.
    void counted_by_heads(std::uint32_t tiles) {
        eye_lead_ = std::max<std::int64_t>(0, eye_lead_ - std::int64_t(tiles));
    }

    bool known() const { return known_; }
    std::uint32_t counter() const { return counter_; }
    std::int64_t eye_lead() const { return eye_lead_; }

  private:
    std::optional<std::string> implausible_speed(double speed, double fastest_asked) const;
    std::optional<std::string> implausible_arrivals(std::uint32_t now, Clock::duration elapsed,
                                                    double fastest_asked) const;
    std::optional<std::string> stuck(double fastest_asked) const;

    drivers::LineConfig line_;
    bool known_ = false;
    std::uint32_t counter_ = 0;
    Clock::time_point previous_{};  // start of the last reading that was counted
    Clock::duration last_took_{};
    std::optional<std::string> fault_;
    // Tiles the photo-eye saw pass that the counter has not counted yet: a few are on their way
    // from the eye to the heads; more, and the counter is stuck.
    std::int64_t eye_lead_ = 0;
    std::optional<std::chrono::nanoseconds> eye_on_since_;
};

}  // namespace tilejet::daemon
