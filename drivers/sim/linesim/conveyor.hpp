#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>

#include "tilejet/drivers/config.hpp"

// The conveyor: an endless train of tiles, tile n's leading edge n * pitch behind tile 0's,
// which starts at 0 (the infeed). Positions are millimetres along the belt; the photo-eye and
// the heads sit at fixed positions downstream. Events are computed at the exact moment a tile
// edge crosses a position, not at the moment the simulator happens to wake up, so their
// timestamps are as precise as a kernel's edge timestamp would be.
namespace tilejet::linesim {

using ns = std::chrono::nanoseconds;

struct ConveyorEvent {
    enum Kind {
        eye_on,
        eye_off,
        at_heads
    } kind;  // leading edge at the eye, trailing edge
             // leaves the eye, leading edge at the heads
    std::uint64_t tile;
    ns time;
};

class Conveyor {
  public:
    explicit Conveyor(const drivers::LineConfig& line) : line_(line) {}

    // Moves the belt to `now` (at the current speed), calling `on_event` for every crossing in
    // time order.
    void advance(ns now, const std::function<void(const ConveyorEvent&)>& on_event);
    // Call advance(now) first, so the old speed applies up to now.
    void set_speed(double mm_s) { speed_ = mm_s; }
    double speed() const { return speed_; }
    // When the next crossing happens at the current speed (nothing when stopped).
    std::optional<ns> next_event(ns now) const;
    bool eye_covered() const {
        return next_[ConveyorEvent::eye_on] > next_[ConveyorEvent::eye_off];
    }

  private:
    double offset(int kind) const;
    double crossing(int kind) const {
        return offset(kind) + double(next_[kind]) * line_.tile_pitch_mm;
    }

    drivers::LineConfig line_;
    double speed_ = 0;     // mm/s
    double position_ = 0;  // belt travel, mm
    ns last_{0};
    bool started_ = false;
    std::uint64_t next_[3] = {0, 0, 0};  // the next tile to cross, per event kind
};

}  // namespace tilejet::linesim
