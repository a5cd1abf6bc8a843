#include "event_hub.hpp"

#include <chrono>

namespace tilejet::api {

namespace {

using namespace std::chrono_literals;
// A line state lasting less than this is not worth a screen update; a tile at full speed
// takes about 400 ms.
constexpr auto kStatusPeriod = 250ms;
constexpr int kJobsEvery = 4;  // the job list changes slower: every 4th status read

std::string sse(const char* event, const std::string& data) {
    return std::string("event: ") + event + "\ndata: " + data + "\n\n";
}

}  // namespace

EventHub::EventHub(ApiBackend& backend, int max_streams, int max_streams_per_session)
    : backend_(backend),
      max_streams_(max_streams),
      max_streams_per_session_(max_streams_per_session),
      thread_([this] { pump(); }) {}

EventHub::~EventHub() {
    close();
    thread_.join();
}

EventHub::Listener::~Listener() {
    std::lock_guard lock(hub.mutex_);
    --hub.listeners_;
    if (--hub.per_session_[session] <= 0) hub.per_session_.erase(session);
}

std::shared_ptr<EventHub::Listener> EventHub::join(const std::string& session) {
    {
        std::lock_guard lock(mutex_);
        if (closing_ || listeners_ >= max_streams_) return nullptr;
        if (const auto it = per_session_.find(session);
            it != per_session_.end() && it->second >= max_streams_per_session_)
            return nullptr;
        ++listeners_;
        ++per_session_[session];
    }
    wake_pump_.notify_all();
    return std::make_shared<Listener>(*this, session);
}

std::optional<std::string> EventHub::next(Listener& l, std::chrono::milliseconds timeout) {
    std::unique_lock lock(mutex_);
    changed_.wait_for(lock, timeout, [&] {
        return closing_ || status_version_ > l.status_seen || jobs_version_ > l.jobs_seen;
    });
    if (closing_) return std::nullopt;
    std::string out;
    if (status_version_ > l.status_seen) out += sse("status", status_);
    if (jobs_version_ > l.jobs_seen) out += sse("jobs", jobs_);
    l.status_seen = status_version_;
    l.jobs_seen = jobs_version_;
    return out;
}

void EventHub::close() {
    {
        std::lock_guard lock(mutex_);
        closing_ = true;
    }
    changed_.notify_all();
    wake_pump_.notify_all();
}

void EventHub::pump() {
    int turn = 0;
    std::unique_lock lock(mutex_);
    while (!closing_) {
        if (listeners_ == 0) {
            wake_pump_.wait(lock, [&] { return closing_ || listeners_ > 0; });
            turn = 0;  // a first listener gets the job list at once
            continue;
        }
        const bool with_jobs = turn++ % kJobsEvery == 0;
        lock.unlock();
        std::string status, jobs;
        try {
            status = backend_.status().dump();
            if (with_jobs) jobs = backend_.jobs().dump();
        } catch (const std::exception& e) {
            status = nlohmann::json{{"error", e.what()}}.dump();
        }
        lock.lock();
        bool news = false;
        if (status != status_) {
            status_ = std::move(status);
            ++status_version_;
            news = true;
        }
        if (with_jobs && !jobs.empty() && jobs != jobs_) {
            jobs_ = std::move(jobs);
            ++jobs_version_;
            news = true;
        }
        if (news) changed_.notify_all();
        wake_pump_.wait_for(lock, kStatusPeriod, [&] { return closing_; });
    }
}

}  // namespace tilejet::api
