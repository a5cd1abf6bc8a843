// /api/status and the operator's commands on the line.
#include "routes.hpp"
#include "tilejet/api/job_request.hpp"

namespace tilejet::api {

void add_line_routes(Router& router, ApiBackend& backend) {
    router.get("/api/status", [&backend](const HttpRequest&, HttpResponse& res) {
        reply_json(res, 200, backend.status());
    });
    router.post(R"(/api/line/(pause|resume|stop|acknowledge))",
                [&backend](const HttpRequest& req, HttpResponse& res) {
                    if (!req.body.empty() && req.body != "{}")
                        throw ApiError(400, "body", "body: this command takes no body");
                    reply_json(res, 200, backend.command(std::string(req.matches[1])));
                });
}

}  // namespace tilejet::api
