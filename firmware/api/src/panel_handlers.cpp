// The operator panel: its page and files, the pictures it shows, and the designs and profiles
// it offers (engineers add to them).
#include <charconv>
#include <regex>

#include "panel_assets.hpp"
#include "routes.hpp"
#include "tilejet/api/job_request.hpp"

namespace tilejet::api {

namespace {

int query_int(const HttpRequest& req, const char* name, int fallback, int min, int max) {
    if (!req.has_param(name)) return fallback;
    const std::string text = req.get_param_value(name);
    int v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size() || v < min || v > max)
        throw ApiError(400, name,
                       std::string(name) + ": expected " + std::to_string(min) + ".." +
                           std::to_string(max) + ", got '" + text + "'");
    return v;
}

std::int64_t path_number(const std::string& text, const char* field) {
    std::int64_t v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size())
        throw ApiError(400, field, std::string(field) + ": '" + text + "' is not a number");
    return v;
}

void reply_png(HttpResponse& res, std::string png, const char* cache) {
    res.set_header("Cache-Control", cache);
    res.set_content(std::move(png), "image/png");
}

}  // namespace

void add_panel_routes(Router& router) {
    for (const PanelAsset& asset : panel_assets()) {
        const std::string name(asset.name);
        // Route patterns are regular expressions: the dot in a file name is escaped.
        std::string path = "/";
        if (name != "index.html") path += std::regex_replace(name, std::regex("\\."), "\\.");
        router.get(path, [&asset](const HttpRequest&, HttpResponse& res) {
            // Asked for again on every load: a daemon updated in place shows its new page.
            res.set_header("Cache-Control", "no-cache");
            res.set_content(std::string(asset.body), std::string(asset.content_type));
        });
    }
}

void add_picture_routes(Router& router, ApiBackend& backend) {
    router
        .get(R"(/api/jobs/(\d+)/tiles/(\d+)\.png)",
             [&backend](const HttpRequest& req, HttpResponse& res) {
                 const auto job = path_number(req.matches[1], "id");
                 const auto index = path_number(req.matches[2], "tile");
                 const int size = query_int(req, "size", 160, 16, 1024);
                 // A tile is a pure function of the job and its index: it never changes.
                 reply_png(res, backend.tile_png(job, index, size), "private, max-age=86400");
             })
        .lane = Lane::pictures;
    router
        .get("/api/wall.png",
             [&backend](const HttpRequest& req, HttpResponse& res) {
                 const int tiles = query_int(req, "tiles", 12, 1, 64);
                 const int size = query_int(req, "size", 640, 64, 2048);
                 reply_png(res, backend.wall_png(tiles, size), "no-store");
             })
        .lane = Lane::pictures;
}

void add_design_routes(Router& router, ApiBackend& backend) {
    router.get("/api/designs", [&backend](const HttpRequest&, HttpResponse& res) {
        reply_json(res, 200, backend.designs());
    });
    router.get("/api/profiles", [&backend](const HttpRequest&, HttpResponse& res) {
        reply_json(res, 200, backend.profiles());
    });
    // Names stay inside the designs' and profiles' folders: no slashes, no leading dot.
    router
        .put(R"(/api/designs/([A-Za-z0-9][A-Za-z0-9._-]{0,99}))",
             [&backend](const HttpRequest& req, HttpResponse& res) {
                 reply_json(res, 201, backend.add_design(req.matches[1], req.body));
             })
        .max_body = kMaxUploadBody;
    router
        .put(R"(/api/profiles/([A-Za-z0-9][A-Za-z0-9._-]{0,99}))",
             [&backend](const HttpRequest& req, HttpResponse& res) {
                 reply_json(res, 201, backend.add_profile(req.matches[1], req.body));
             })
        .max_body = kMaxUploadBody;
    router.post("/api/config/reload", [&backend](const HttpRequest& req, HttpResponse& res) {
        if (!req.body.empty() && req.body != "{}")
            throw ApiError(400, "body", "body: this command takes no body");
        reply_json(res, 200, backend.reload_config());
    });
}

}  // namespace tilejet::api
