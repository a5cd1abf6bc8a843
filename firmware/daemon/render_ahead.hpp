#pragma once

// RenderAhead: the next tiles' separations rendered on a pool of threads before the heads need
// them. The queue is bounded: at most `capacity` tiles are rendered or in work, so memory stays
// fixed however long the job; the print loop says which tiles it wants next, in order.
#include <condition_variable>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "loop_clock.hpp"
#include "separations.hpp"
#include "tile_renderer.hpp"

namespace tilejet::daemon {

class RenderAhead {
  public:
    // threads: tiles render on a pool of `threads` (0: one per core) while the loop does other
    // things. in_caller: a wanted tile renders when it is taken, in the caller's thread, so
    // every wanted tile counts as ready: a test on a stepped clock sees the same run every time.
    enum class Mode { threads, in_caller };
    RenderAhead(int threads, int capacity, Mode mode = Mode::threads);
    // in_caller: a tile is ready `per_tile` of `clock`'s time after the tile before it, or
    // after it was first wanted, as if one render thread of that speed rendered ahead: on a
    // stepped clock a test makes rendering fall behind the line, the same way every time.
    void pace(const LoopClock& clock, LoopClock::Clock::duration per_tile);
    ~RenderAhead();
    RenderAhead(const RenderAhead&) = delete;
    RenderAhead& operator=(const RenderAhead&) = delete;

    // The tiles to have ready, next first (only the first `capacity` count). Tiles no longer
    // wanted are dropped.
    void want(std::shared_ptr<const TileRenderer> renderer, const std::vector<std::int64_t>& next);
    // The rendered tile, removed from the queue; nothing when it is not ready yet.
    std::optional<Separations> take(std::int64_t job, std::int64_t index);
    // How many of the wanted tiles are ready.
    int ready() const;
    // How many tiles are wanted (at most `capacity`).
    int wanted() const;
    int capacity() const { return capacity_; }
    // A sent tile's bytes, kept to render a later tile into (at most `capacity` are kept).
    void recycle(Separations&& tile);
    // The last render failure, cleared by reading it.
    std::optional<std::string> take_error();

  private:
    using Key = std::pair<std::int64_t, std::int64_t>;  // job, tile index
    struct Slot {
        bool working = false;
        std::optional<Separations> tile;
        LoopClock::Clock::time_point ready_at{};  // paced in_caller only
    };
    // Paced in_caller: whether the slot's time has come.
    bool due(const Slot& slot) const;
    void work();

    int capacity_;
    Mode mode_;
    const LoopClock* pace_clock_ = nullptr;
    LoopClock::Clock::duration per_tile_{};
    LoopClock::Clock::time_point paced_until_{};  // when the paced render thread is free
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    bool stop_ = false;
    std::shared_ptr<const TileRenderer> renderer_;
    std::vector<Key> wanted_;
    std::map<Key, Slot> slots_;
    std::optional<std::string> error_;
    std::vector<std::vector<std::uint8_t>> spare_;
    std::vector<std::jthread> workers_;
};

}  // namespace tilejet::daemon
