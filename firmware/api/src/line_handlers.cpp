// /api/status and the operator's commands on the line.
#include "routes.hpp"
#include "tilejet/api/job_request.hpp"

namespace tilejet::api {

void add_line_routes(httplib::Server& server, ApiBackend& backend) {
    server.Get("/api/status", [&backend](const httplib::Request&, httplib::Response& res) {
        reply_json(res, 200, backend.status());
    });
    server.Post(R"(/api/line/(pause|resume|stop|acknowledge))",
                [&backend](const httplib::Request& req, httplib::Response& res) {
                    if (!req.body.empty() && req.body != "{}")
                        throw ApiError(400, "body", "body: this command takes no body");
                    reply_json(res, 200, backend.command(std::string(req.matches[1])));
                });
}

}  // namespace tilejet::api
