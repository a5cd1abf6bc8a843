#pragma once

// EventHub: the live feed behind /api/events (server-sent events). One pump thread reads the
// backend's status and job list while somebody listens and publishes what changed; every
// stream waits on the hub, so a hundred open panels cost the backend what one does.
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "tilejet/api/api_backend.hpp"

namespace tilejet::api {

class EventHub {
  public:
    EventHub(ApiBackend& backend, int max_streams);
    ~EventHub();
    EventHub(const EventHub&) = delete;
    EventHub& operator=(const EventHub&) = delete;

    // What one stream has seen so far; counts as a listener while it lives.
    struct Listener {
        explicit Listener(EventHub& hub) : hub(hub) {}
        ~Listener();
        EventHub& hub;
        std::uint64_t status_seen = 0, jobs_seen = 0;
    };
    // A new listener, or null when max_streams are open.
    std::shared_ptr<Listener> join();

    // The events `listener` has not seen, as SSE text; empty after `timeout` with nothing new.
    // nullopt once the hub is closing.
    std::optional<std::string> next(Listener& listener, std::chrono::milliseconds timeout);

    // Wakes every stream with "closing"; called before the server stops.
    void close();

  private:
    void pump();
    ApiBackend& backend_;
    const int max_streams_;
    std::mutex mutex_;
    std::condition_variable changed_, wake_pump_;
    bool closing_ = false;
    int listeners_ = 0;
    std::string status_, jobs_;  // the last published, as JSON text
    std::uint64_t status_version_ = 0, jobs_version_ = 0;
    std::thread thread_;
};

}  // namespace tilejet::api
