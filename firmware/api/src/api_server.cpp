#include "tilejet/api/api_server.hpp"

#include <httplib.h>

#include <stdexcept>

#include "routes.hpp"
#include "tilejet/api/job_request.hpp"

namespace tilejet::api {

void reply_json(httplib::Response& res, int status, const nlohmann::json& body) {
    res.status = status;
    res.set_content(body.dump() + "\n", "application/json");
}

void reply_error(httplib::Response& res, int status, const std::string& field,
                 const std::string& message) {
    nlohmann::json j{{"error", message}};
    if (!field.empty()) j["field"] = field;
    reply_json(res, status, j);
}

ApiServer::ApiServer(ApiBackend& backend, const std::string& host, int port)
    : server_(std::make_unique<httplib::Server>()) {
    if (!(host == "localhost" || host == "::1" || host.starts_with("127.")))
        throw std::invalid_argument("API: '" + host + "' is not a loopback address");
    server_->set_payload_max_length(kMaxBodyBytes);
    server_->set_read_timeout(5, 0);
    server_->set_write_timeout(5, 0);
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
        const std::string what = res.status == 413   ? "body: too large"
                                 : res.status == 404 ? "no such resource"
                                                     : "request refused";
        reply_error(res, res.status, res.status == 413 ? "body" : "", what);
    });
    add_job_routes(*server_, backend);
    add_line_routes(*server_, backend);
    port_ = port == 0 ? server_->bind_to_any_port(host)
                      : (server_->bind_to_port(host, port) ? port : -1);
    if (port_ <= 0)
        throw std::runtime_error("API: cannot listen on " + host + ":" + std::to_string(port));
    thread_ = std::thread([this] { server_->listen_after_bind(); });
}

ApiServer::~ApiServer() {
    server_->stop();
    if (thread_.joinable()) thread_.join();
}

}  // namespace tilejet::api
