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
}  // namespace

void add_event_routes(httplib::Server& server, EventHub& hub, Gate& gate) {
    server.Get("/api/events", [&hub, &gate](const httplib::Request& req, httplib::Response& res) {
        auto listener = hub.join();
        if (!listener) throw ApiError(503, "", "too many open event streams; try again later");
        const std::string session = session_cookie(req).value_or("");
        res.set_header("Cache-Control", "no-store");
        auto first = std::make_shared<bool>(true);
        res.set_chunked_content_provider(
            "text/event-stream",
            [listener, session, first, &hub, &gate](size_t, httplib::DataSink& sink) {
                std::string text;
                if (*first) {
                    // The browser's EventSource waits this long before it reconnects.
                    text = "retry: 2000\n\n";
                    *first = false;
                }
                const auto events = hub.next(*listener, kKeepAlive);
                // Signed out or expired: the stream ends, the panel's reconnect gets 401.
                if (!events || !gate.alive(session)) {
                    sink.done();
                    return true;
                }
                text += events->empty() ? ": keep-alive\n\n" : *events;
                return sink.write(text.data(), text.size());
            });
    });
}

}  // namespace tilejet::api
