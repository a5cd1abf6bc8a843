#include "render_ahead.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>

namespace tilejet::daemon {

namespace {

// Render threads yield to the print loop, the GPIO and API threads: those are idle most of the
// time but must run the moment a tile passes (a send in the quiet time before the next tile),
// while rendering only has to keep the queue full. Measured with tilejet-daemon-bench on the
// 2-core controller: without it, sends ended too close to a tile's arrival (each a conveyor stop
// for a resync) at 16000-20000 mm/s; with it, none up to 20000 mm/s.
constexpr int kRenderNiceness = 10;

void yield_to_the_line() {
    const pid_t self = ::gettid();
    errno = 0;
    const int now = ::getpriority(PRIO_PROCESS, id_t(self));
    if (errno == 0) ::setpriority(PRIO_PROCESS, id_t(self), now + kRenderNiceness);
}

}  // namespace

RenderAhead::RenderAhead(int threads, int capacity, Mode mode)
    : capacity_(std::max(1, capacity)), mode_(mode) {
    if (mode_ == Mode::in_caller) return;
    if (threads <= 0) threads = int(std::max(1u, std::thread::hardware_concurrency()));
    for (int i = 0; i < threads; ++i)
        workers_.emplace_back([this] { work(); });
}

RenderAhead::~RenderAhead() {
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
}

void RenderAhead::pace(const LoopClock& clock, LoopClock::Clock::duration per_tile) {
    std::lock_guard lock(mutex_);
    pace_clock_ = &clock;
    per_tile_ = per_tile;
}

bool RenderAhead::due(const Slot& slot) const {
    return !pace_clock_ || slot.ready_at <= pace_clock_->now();
}

void RenderAhead::want(std::shared_ptr<const TileRenderer> renderer,
                       const std::vector<std::int64_t>& next) {
    std::lock_guard lock(mutex_);
    renderer_ = std::move(renderer);
    wanted_.clear();
    const std::int64_t job = renderer_ ? renderer_->job() : -1;
    for (std::int64_t index : next) {
        if (int(wanted_.size()) >= capacity_) break;
        wanted_.push_back({job, index});
    }
    for (auto it = slots_.begin(); it != slots_.end();) {
        const bool keep = std::find(wanted_.begin(), wanted_.end(), it->first) != wanted_.end();
        if (!keep && !it->second.working)
            it = slots_.erase(it);
        else
            ++it;
    }
    for (const Key& k : wanted_) {
        const auto [it, added] = slots_.try_emplace(k);
        if (added && pace_clock_) {
            paced_until_ = std::max(paced_until_, pace_clock_->now()) + per_tile_;
            it->second.ready_at = paced_until_;
        }
    }
    wake_.notify_all();
}

std::optional<Separations> RenderAhead::take(std::int64_t job, std::int64_t index) {
    std::lock_guard lock(mutex_);
    auto it = slots_.find({job, index});
    if (mode_ == Mode::in_caller && it != slots_.end() && !it->second.tile && renderer_) {
        if (!due(it->second)) return std::nullopt;
        try {
            it->second.tile = renderer_->render(index, 1, {});
        } catch (const std::exception& e) {
            error_ = "tile " + std::to_string(index) + ": " + e.what();
            return std::nullopt;
        }
    }
    if (it == slots_.end() || !it->second.tile) return std::nullopt;
    std::optional<Separations> tile = std::move(it->second.tile);
    slots_.erase(it);
    std::erase(wanted_, Key{job, index});
    return tile;
}

int RenderAhead::ready() const {
    std::lock_guard lock(mutex_);
    if (mode_ == Mode::in_caller)
        return int(std::count_if(wanted_.begin(), wanted_.end(), [&](const Key& k) {
            const auto it = slots_.find(k);
            return it != slots_.end() && due(it->second);
        }));
    int n = 0;
    for (const Key& k : wanted_) {
        auto it = slots_.find(k);
        if (it != slots_.end() && it->second.tile) ++n;
    }
    return n;
}

int RenderAhead::wanted() const {
    std::lock_guard lock(mutex_);
    return int(wanted_.size());
}

void RenderAhead::recycle(Separations&& tile) {
    std::lock_guard lock(mutex_);
    if (int(spare_.size()) < capacity_) spare_.push_back(std::move(tile.bytes));
}

std::optional<std::string> RenderAhead::take_error() {
    std::lock_guard lock(mutex_);
    return std::exchange(error_, std::nullopt);
}

void RenderAhead::work() {
    yield_to_the_line();
    std::unique_lock lock(mutex_);
    while (true) {
        Key key{};
        bool found = false;
        wake_.wait(lock, [&] {
            if (stop_) return true;
            for (const Key& k : wanted_) {
                auto it = slots_.find(k);
                if (it != slots_.end() && !it->second.working && !it->second.tile) {
                    key = k;
                    found = true;
                    return true;
                }
            }
            return false;
        });
        if (stop_) return;
        if (!found) continue;
        slots_[key].working = true;
        const auto renderer = renderer_;
        std::vector<std::uint8_t> buffer;
        if (!spare_.empty()) {
            buffer = std::move(spare_.back());
            spare_.pop_back();
        }
        lock.unlock();
        std::optional<Separations> tile;
        std::string error;
        try {
            tile = renderer->render(key.second, 1, std::move(buffer));
        } catch (const std::exception& e) {
            error = "tile " + std::to_string(key.second) + ": " + e.what();
        }
        lock.lock();
        auto it = slots_.find(key);
        if (!error.empty()) {
            error_ = error;
            if (it != slots_.end()) it->second.working = false;
            continue;
        }
        const bool wanted = std::find(wanted_.begin(), wanted_.end(), key) != wanted_.end();
        if (it != slots_.end() && wanted) {
            it->second.working = false;
            it->second.tile = std::move(tile);
        } else if (it != slots_.end()) {
            slots_.erase(it);
        }
    }
}

}  // namespace tilejet::daemon
