#pragma once

// HeadMirror: what the print heads hold as the daemon knows it (the tiles it sent, oldest
// first) and whether that can be trusted. Pure and clock-free: the print loop tells it what
// happened (a send, a tile reaching the heads, the heads losing their buffer, their count at a
// resync) and writes what it answers to the job store. Exactly-once rules 1-3 in
// print_loop.hpp rest on its arithmetic, which tests/firmware/test_head_mirror.cpp checks
// over every small case.
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "tilejet/jobs/job.hpp"

namespace tilejet::daemon {

struct HeadEntry {
    std::int64_t job = 0;
    std::int64_t index = 0;  // < 0: a blank sent to probe the heads; unknown: -1
    bool known = true;       // false: something the heads held that the store never saw
    bool is_tile() const { return known && index >= 0; }
};

// What a resync found, from the tiles the store says went to the heads and how many of them
// the heads still hold.
struct ResyncPlan {
    // Set when the store's newest tile was `sending` (the daemon stopped mid-send): whether it
    // reached the heads.
    std::optional<bool> last_sending_reached;
    std::vector<HeadEntry> printed;  // sent before and printed since: the oldest
    int unknown = 0;                 // held tiles the store never sent: they pass as blanks
    std::vector<HeadEntry> held;     // sent before and still in the heads: the newest
};

class HeadMirror {
  public:
    bool certain() const { return certain_; }
    // Something happened the mirror cannot follow (a crash, a lost link, a late send, a
    // lying counter): nothing prints until a resync.
    void doubt() { certain_ = false; }
    std::size_t size() const { return entries_.size(); }
    bool empty() const { return entries_.empty(); }
    bool holds_tiles() const;  // any job tile (not blanks)
    bool holds_tiles_of(std::int64_t job) const;

    void sent(const HeadEntry& e) { entries_.push_back(e); }
    // A tile reached the heads with print-enable on: the oldest entry was printed on it.
    std::optional<HeadEntry> arrived();
    // The heads emptied their buffer (a restart): the oldest `count` entries are gone.
    std::vector<HeadEntry> lose_oldest(std::size_t count);
    // Nothing is in the heads and nothing can be on its way: certain.
    void known_empty();
    // A resync could not finish: the next one starts over.
    void forget() { entries_.clear(); }

    // The heads answered FULL after the probes of a resync: `held` older tiles are still in
    // them (capacity minus probes taken; 0 when they never answered FULL). The heads are a
    // FIFO, so those are the newest of `queued` (the store's sent and sending tiles, oldest
    // first); the older ones were printed.
    static ResyncPlan plan_resync(const std::vector<jobs::QueuedTile>& queued, int held);
    // After the resync: unknown blanks, then the held tiles, then the probes. Certain.
    void adopt(const ResyncPlan& plan, const std::vector<HeadEntry>& probes);

  private:
    std::deque<HeadEntry> entries_;
    bool certain_ = false;  // start-up: whatever a previous run left in the heads is unknown
};

}  // namespace tilejet::daemon
