#include "head_mirror.hpp"

#include <algorithm>

namespace tilejet::daemon {

bool HeadMirror::holds_tiles() const {
    return std::any_of(entries_.begin(), entries_.end(),
                       [](const HeadEntry& e) { return e.is_tile(); });
}

bool HeadMirror::holds_tiles_of(std::int64_t job) const {
    return std::any_of(entries_.begin(), entries_.end(),
                       [&](const HeadEntry& e) { return e.is_tile() && e.job == job; });
}

std::optional<HeadEntry> HeadMirror::arrived() {
    if (entries_.empty()) return std::nullopt;
    const HeadEntry e = entries_.front();
    entries_.pop_front();
    return e;
}

std::vector<HeadEntry> HeadMirror::lose_oldest(std::size_t count) {
    std::vector<HeadEntry> lost;
    for (std::size_t i = 0; i < count && !entries_.empty(); ++i) {
        lost.push_back(entries_.front());
        entries_.pop_front();
    }
    return lost;
}

void HeadMirror::known_empty() {
    entries_.clear();
    certain_ = true;
}

ResyncPlan HeadMirror::plan_resync(const std::vector<jobs::QueuedTile>& queued, int held) {
    ResyncPlan plan;
    std::vector<jobs::QueuedTile> olds = queued;
    held = std::max(0, held);
    if (!olds.empty() && olds.back().state == jobs::TileState::sending) {
        // The daemon stopped between marking it and hearing back. No tile can reach the heads
        // during a send (rule 2), so it got there unless the heads hold one fewer than sent.
        plan.last_sending_reached = held != int(olds.size()) - 1;
        if (!*plan.last_sending_reached) olds.pop_back();
    }
    plan.unknown = std::max(0, held - int(olds.size()));
    const int printed = int(olds.size()) - std::min(held, int(olds.size()));
    for (int i = 0; i < int(olds.size()); ++i)
        (i < printed ? plan.printed : plan.held)
            .push_back({olds[size_t(i)].job, olds[size_t(i)].index, true});
    return plan;
}

void HeadMirror::adopt(const ResyncPlan& plan, const std::vector<HeadEntry>& probes) {
    entries_.clear();
    for (int i = 0; i < plan.unknown; ++i)
        entries_.push_back({0, -1, false});
    entries_.insert(entries_.end(), plan.held.begin(), plan.held.end());
    entries_.insert(entries_.end(), probes.begin(), probes.end());
    certain_ = true;
}

}  // namespace tilejet::daemon
