#include "tilejet/api/api_server.hpp"

#include <stdexcept>

#include "event_hub.hpp"
#include "gate.hpp"
#include "http_server.hpp"
#include "routes.hpp"
#include "tilejet/api/job_request.hpp"

namespace tilejet::api {

void reply_json(HttpResponse& res, int status, const nlohmann::json& body) {
    res.status = status;
    // Error messages quote what the client sent (a path, a query value, the JSON parser's "last
    // read"), which need not be UTF-8: replaced with U+FFFD rather than thrown from the
    // exception handler, where it would end the daemon.
    res.set_content(body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n",
                    "application/json");
}

void reply_error(HttpResponse& res, int status, const std::string& field,
                 const std::string& message) {
    nlohmann::json j{{"error", message}};
    if (!field.empty()) j["field"] = field;
    reply_json(res, status, j);
}

ApiServer::ApiServer(ApiBackend& backend, const std::string& host, int port,
                     const AccessSettings& access)
    : gate_(std::make_unique<Gate>(access)),
      events_(std::make_unique<EventHub>(backend, access.limits.event_streams,
                                         access.limits.event_streams_per_session)),
      router_(std::make_unique<Router>()) {
    add_session_routes(*router_, *gate_);
    add_event_routes(*router_, *events_, *gate_);
    add_job_routes(*router_, backend);
    add_line_routes(*router_, backend);
    add_picture_routes(*router_, backend);
    add_design_routes(*router_, backend);
    add_panel_routes(*router_);
    HttpServer::Hooks hooks;
    hooks.before = [this](const HttpRequest& req, HttpResponse& res) {
        return gate_->check(req, res);
    };
    hooks.after = [](HttpResponse& res) {
        // The panel loads nothing from elsewhere and is never framed (clickjacking a Stop).
        res.set_header("Content-Security-Policy",
                       "default-src 'self'; img-src 'self' data:; frame-ancestors 'none'; "
                       "base-uri 'none'; form-action 'self'");
        res.set_header("X-Content-Type-Options", "nosniff");
        res.set_header("X-Frame-Options", "DENY");
        res.set_header("Referrer-Policy", "no-referrer");
    };
    server_ = std::make_unique<HttpServer>(*router_, std::move(hooks), access.limits, host, port);
}

ApiServer::~ApiServer() {
    events_->close();
    server_.reset();
}

int ApiServer::port() const {
    return server_->port();
}

}  // namespace tilejet::api
