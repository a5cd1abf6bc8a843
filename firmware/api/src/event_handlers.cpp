// /api/events: server-sent events for the panel (EventSource reconnects by itself).
#include "event_hub.hpp"
#include "gate.hpp"
#include "routes.hpp"
#include "tilejet/api/job_request.hpp"

namespace tilejet::api {

namespace {

// A comment line this often finds out a panel that went away (the write fails) and keeps
// proxies from closing a quiet stream.
constexpr std::chrono::seconds kKeepAlive{10};

class EventStream : public BodyStream {
  public:
    EventStream(std::shared_ptr<EventHub::Listener> listener, std::string session, EventHub& hub,
                Gate& gate)
        : listener_(std::move(listener)), session_(std::move(session)), hub_(hub), gate_(gate) {}

    std::optional<std::string> poll() override {
        std::string text;
        if (first_) {
            // The browser's EventSource waits this long before it reconnects.
            text = "retry: 2000\n\n";
            first_ = false;
        }
        const auto events = hub_.next(*listener_, std::chrono::milliseconds(0));
        // Signed out or expired: the stream ends, the panel's reconnect gets 401.
        if (!events || !gate_.alive(session_)) return std::nullopt;
        const auto now = std::chrono::steady_clock::now();
        if (!events->empty())
            text += *events;
        else if (now - last_sent_ >= kKeepAlive)
            text += ": keep-alive\n\n";
        if (!text.empty()) last_sent_ = now;
        return text;
    }

  private:
    std::shared_ptr<EventHub::Listener> listener_;
    std::string session_;
    EventHub& hub_;
    Gate& gate_;
    bool first_ = true;
    std::chrono::steady_clock::time_point last_sent_ = std::chrono::steady_clock::now();
};

}  // namespace

void add_event_routes(Router& router, EventHub& hub, Gate& gate) {
    router.get("/api/events", [&hub, &gate](const HttpRequest& req, HttpResponse& res) {
        const std::string session = session_cookie(req).value_or("");
        auto listener = hub.join(session);
        if (!listener) throw ApiError(503, "", "too many open event streams; try again later");
        res.set_header("Cache-Control", "no-store");
        res.set_stream(std::make_shared<EventStream>(std::move(listener), session, hub, gate),
                       "text/event-stream");
    });
}

}  // namespace tilejet::api
