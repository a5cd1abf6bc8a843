#include "tilejet/api/api_server.hpp"

#include <httplib.h>

#include <stdexcept>

#include "event_hub.hpp"
#include "gate.hpp"
#include "routes.hpp"
#include "tilejet/api/job_request.hpp"

namespace tilejet::api {

namespace {

// Uploaded maps and profiles are the largest bodies; JSON routes hold theirs to kMaxBodyBytes.
constexpr std::size_t kMaxUploadBytes = 16 * 1024 * 1024;
// Requests other than event streams are short; these threads are always there for them.
constexpr int kRequestThreads = 8;

}  // namespace

void reply_json(httplib::Response& res, int status, const nlohmann::json& body) {
    res.status = status;
    // Error messages quote what the client sent (a path, a query value, the JSON parser's "last
    // read"), which need not be UTF-8: replaced with U+FFFD rather than thrown from the
    // exception handler, where it would end the daemon.
    res.set_content(body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n",
                    "application/json");
}

void reply_error(httplib::Response& res, int status, const std::string& field,
                 const std::string& message) {
    nlohmann::json j{{"error", message}};
    if (!field.empty()) j["field"] = field;
    reply_json(res, status, j);
}

ApiServer::ApiServer(ApiBackend& backend, const std::string& host, int port,
                     const AccessSettings& access)
    : gate_(std::make_unique<Gate>(access)),
      events_(std::make_unique<EventHub>(backend, access.event_streams)),
      server_(std::make_unique<httplib::Server>()) {
    const int threads = access.event_streams + kRequestThreads;
    // httplib owns the queue it gets (its interface takes a plain pointer).
    server_->new_task_queue = [threads] { return new httplib::ThreadPool(size_t(threads)); };
    server_->set_payload_max_length(kMaxUploadBytes);
    server_->set_read_timeout(5, 0);
    server_->set_write_timeout(5, 0);
    // An idle keep-alive connection holds its thread until this runs out, shutdown included.
    server_->set_keep_alive_timeout(2);
    server_->set_exception_handler([](const auto&, auto& res, std::exception_ptr ep) {
        try {
            std::rethrow_exception(ep);
        } catch (const ApiError& e) {
            reply_error(res, e.status(), e.field(), e.what());
        } catch (const std::exception& e) {
            reply_error(res, 500, "", e.what());
        }
    });
    server_->set_error_handler([](const httplib::Request&, httplib::Response& res) {
        if (!res.body.empty()) return;
        // An oversize body is a bad request like any other bad field (400, naming it), not
        // cpp-httplib's 413: clients handle one kind of refusal.
        if (res.status == 413) return reply_error(res, 400, "body", "body: too large");
        reply_error(res, res.status, "",
                    res.status == 404 ? "no such resource" : "request refused");
    });
    server_->set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
        return gate_->check(req, res);
    });
    server_->set_post_routing_handler([](const httplib::Request&, httplib::Response& res) {
        // The panel loads nothing from elsewhere and is never framed (clickjacking a Stop).
        res.set_header("Content-Security-Policy",
                       "default-src 'self'; img-src 'self' data:; frame-ancestors 'none'; "
                       "base-uri 'none'; form-action 'self'");
        res.set_header("X-Content-Type-Options", "nosniff");
        res.set_header("X-Frame-Options", "DENY");
        res.set_header("Referrer-Policy", "no-referrer");
    });
    add_session_routes(*server_, *gate_);
    add_event_routes(*server_, *events_, *gate_);
    add_job_routes(*server_, backend);
    add_line_routes(*server_, backend);
    add_picture_routes(*server_, backend);
    add_design_routes(*server_, backend);
    add_panel_routes(*server_);
    port_ = port == 0 ? server_->bind_to_any_port(host)
                      : (server_->bind_to_port(host, port) ? port : -1);
    if (port_ <= 0)
        throw std::runtime_error("API: cannot listen on " + host + ":" + std::to_string(port));
    thread_ = std::thread([this] { server_->listen_after_bind(); });
}

ApiServer::~ApiServer() {
    events_->close();
    server_->stop();
    if (thread_.joinable()) thread_.join();
}

}  // namespace tilejet::api
