// /api/jobs: submit, list, show.
#include <charconv>

#include "routes.hpp"
#include "tilejet/api/job_request.hpp"

namespace tilejet::api {

nlohmann::json job_json(const jobs::Job& job) {
    return {{"id", job.id},
            {"name", job.name()},
            {"status", std::string(to_string(job.status))},
            {"message", job.message},
            {"map", job.spec.map},
            {"map_id", job.spec.map_id},
            {"profile", job.spec.profile},
            {"seed", job.spec.seed},
            {"tiles", job.spec.tiles},
            {"tile_mm", {job.spec.tile_width_mm, job.spec.tile_height_mm}},
            {"dpi", job.spec.dpi},
            {"layout", job.spec.layout},
            {"wall_width", job.spec.wall_width},
            {"printed", job.printed},
            {"spoiled", job.spoiled},
            {"missed", job.missed},
            {"missed_line_tiles", job.missed_line_tiles},
            {"created", job.created},
            {"started", job.started},
            {"finished", job.finished}};
}

void add_job_routes(Router& router, ApiBackend& backend) {
    router.post("/api/jobs", [&backend](const HttpRequest& req, HttpResponse& res) {
        const jobs::JobSpec spec = parse_job_request(req.body, backend.default_dpi());
        reply_json(res, 201, backend.submit(spec));
    });
    router.get("/api/jobs", [&backend](const HttpRequest&, HttpResponse& res) {
        reply_json(res, 200, backend.jobs());
    });
    router.get(R"(/api/jobs/([^/]+))", [&backend](const HttpRequest& req, HttpResponse& res) {
        const std::string text = req.matches[1];
        std::int64_t id = 0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), id);
        if (ec != std::errc() || end != text.data() + text.size() || id <= 0)
            throw ApiError(400, "id", "id: '" + text + "' is not a job number");
        const auto job = backend.job(id);
        if (!job) throw ApiError(404, "id", "no job " + text);
        reply_json(res, 200, *job);
    });
}

}  // namespace tilejet::api
