#pragma once

// What the HTTP handlers ask of the daemon. The daemon implements it; tests can too. Errors
// are ApiError (job_request.hpp) with the status to answer.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>

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
    virtual int default_dpi() const = 0;
};

// A job as the API shows it.
nlohmann::json job_json(const jobs::Job& job);

}  // namespace tilejet::api
