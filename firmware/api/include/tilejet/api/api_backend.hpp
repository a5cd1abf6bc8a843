#pragma once

// What the HTTP handlers ask of the daemon. The daemon implements it; tests can too. Errors
// are ApiError (job_request.hpp) with the status to answer.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "tilejet/api/access.hpp"
#include "tilejet/jobs/job.hpp"

namespace tilejet::api {

class ApiBackend {
  public:
    virtual ~ApiBackend() = default;
    virtual nlohmann::json status() = 0;
    // Checks that the map and profile load, then queues the job.
    virtual nlohmann::json submit(const jobs::JobSpec& spec) = 0;
    virtual nlohmann::json jobs() = 0;
    virtual std::optional<nlohmann::json> job(std::int64_t id) = 0;
    // "pause" | "resume" | "stop" | "acknowledge"
    virtual nlohmann::json command(std::string_view name) = 0;
    // The dpi of jobs that give none; 0: submit takes the design's.
    virtual int default_dpi() const = 0;
    // Who may sign in, and the session and sign-in limits (the config's [api] and [[users]]).
    virtual AccessSettings access() const { return {}; }

    // The panel's pictures, PNG bytes: an sRGB soft proof of tile `index` of job `job` at most
    // `max_side` pixels on its longer side, and the last `tiles` printed tiles as a wall.
    virtual std::string tile_png(std::int64_t job, std::int64_t index, int max_side);
    virtual std::string wall_png(int tiles, int max_side);

    // Designs (texture maps) and CMYK profiles the line has: [{"name", "path", ...}].
    virtual nlohmann::json designs();
    virtual nlohmann::json profiles();
    // An engineer's upload; `bytes` is the file. Checked (it loads) before it is kept.
    virtual nlohmann::json add_design(const std::string& name, const std::string& bytes);
    virtual nlohmann::json add_profile(const std::string& name, const std::string& bytes);
    // Re-reads the config file (what can change without a restart).
    virtual nlohmann::json reload_config();
};

// A job as the API shows it.
nlohmann::json job_json(const jobs::Job& job);

}  // namespace tilejet::api
