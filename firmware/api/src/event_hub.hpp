#pragma once

// EventHub: the live feed behind /api/events (server-sent events). One pump thread reads the
// backend's status and job list while somebody listens and publishes what changed; every
// stream waits on the hub, so a hundred open panels cost the backend what one does.
#include <condition_variable>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "tilejet/api/api_backend.hpp"

namespace tilejet::api {

class EventHub {
  public:
    EventHub(ApiBackend& backend, int max_streams, int max_streams_per_session);
    ~EventHub();
    EventHub(const EventHub&) = delete;
    EventHub& operator=(const EventHub&) = delete;

    // What one stream has seen so far; counts as a listener while it lives.
    struct Listener {
        Listener(EventHub& hub, std::string session) : hub(hub), session(std::move(session)) {}
        ~Listener();
        EventHub& hub;
        const std::string session;
        std::uint64_t status_seen = 0, jobs_seen = 0;
    };
    // A new listener for a stream of `session`, or null when max_streams are open, or
    // max_streams_per_session of this session's (one viewer cannot take every stream).
    std::shared_ptr<Listener> join(const std::string& session);

    // The events `listener` has not seen, as SSE text; empty after `timeout` with nothing new.
    // nullopt once the hub is closing.
    std::optional<std::string> next(Listener& listener, std::chrono::milliseconds timeout);

    // Wakes every stream with "closing"; called before the server stops.
    void close();

  private:
    void pump();
    ApiBackend& backend_;
    const int max_streams_, max_streams_per_session_;
    std::mutex mutex_;
    std::condition_variable changed_, wake_pump_;
    bool closing_ = false;
    int listeners_ = 0;
    std::map<std::string, int> per_session_;
    std::string status_, jobs_;  // the last published, as JSON text
    std::uint64_t status_version_ = 0, jobs_version_ = 0;
    std::thread thread_;
};

}  // namespace tilejet::api
