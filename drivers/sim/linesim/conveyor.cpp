#include "conveyor.hpp"

namespace tilejet::linesim {

double Conveyor::offset(int kind) const {
    switch (kind) {
        case ConveyorEvent::eye_on:
            return line_.photo_eye_mm;
        case ConveyorEvent::eye_off:
            return line_.photo_eye_mm + line_.tile_length_mm;
        default:
            return line_.heads_mm;
    }
}

void Conveyor::advance(ns now, const std::function<void(const ConveyorEvent&)>& on_event) {
    if (!started_ || now < last_) {
        started_ = true;
        last_ = now;
        return;
    }
    const double target = position_ + speed_ * std::chrono::duration<double>(now - last_).count();
    while (speed_ > 0) {
        int kind = 0;
        for (int k = 1; k < 3; ++k)
            if (crossing(k) < crossing(kind)) kind = k;
        const double at = crossing(kind);
        if (at > target) break;
        const ns when = last_ + ns(std::int64_t((at - position_) / speed_ * 1e9));
        ++next_[kind];
        on_event({ConveyorEvent::Kind(kind), next_[kind] - 1, when});
    }
    position_ = target;
    last_ = now;
}

std::optional<ns> Conveyor::next_event(ns now) const {
    if (speed_ <= 0) return std::nullopt;
    double at = crossing(0);
    for (int k = 1; k < 3; ++k)
        at = std::min(at, crossing(k));
    const double seconds = (at - position_) / speed_;
    return now + ns(std::int64_t(seconds * 1e9) + 1);
}

}  // namespace tilejet::linesim
