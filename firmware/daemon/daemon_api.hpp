#pragma once

// DaemonApi: the API's view of the daemon: the job store (its own connection) for jobs, the
// controller for state and commands, TilePreviews for the panel's pictures.
#include <chrono>
#include <deque>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>

#include "controller.hpp"
#include "daemon_config.hpp"
#include "tile_previews.hpp"
#include "tilejet/api/api_backend.hpp"
#include "tilejet/jobs/job_store.hpp"

namespace tilejet::daemon {

class DaemonApi : public api::ApiBackend {
  public:
    DaemonApi(const DaemonConfig& config, Controller& controller);

    nlohmann::json status() override;
    nlohmann::json submit(const jobs::JobSpec& spec) override;
    nlohmann::json jobs() override;
    std::optional<nlohmann::json> job(std::int64_t id) override;
    nlohmann::json command(std::string_view name) override;
    // A job that gives no dpi prints its design at the design's dpi (submit).
    int default_dpi() const override { return 0; }
    api::AccessSettings access() const override { return config_.api.access; }

    std::string tile_png(std::int64_t job, std::int64_t index, int max_side) override;
    std::string wall_png(int tiles, int max_side) override;
    nlohmann::json designs() override;
    nlohmann::json profiles() override;
    nlohmann::json add_design(const std::string& name, const std::string& bytes) override;
    nlohmann::json add_profile(const std::string& name, const std::string& bytes) override;
    // SIGHUP to this process: main's signal loop reloads, exactly as `kill -HUP` would.
    nlohmann::json reload_config() override;

  private:
    double rate_tiles_per_min(std::int64_t printed);
    std::optional<jobs::Job> wall_job(const LineSnapshot& s);
    // The dpi a design file is built for; nothing when it records none or is no map.
    std::optional<double> design_dpi(const std::string& path);

    DaemonConfig config_;
    Controller& controller_;
    std::mutex mutex_;  // the store's connection and the rate samples
    jobs::JobStore store_;
    std::deque<std::pair<std::chrono::steady_clock::time_point, std::int64_t>> rate_samples_;
    TilePreviews previews_;
    struct DesignDpi {
        std::uintmax_t size = 0;
        std::filesystem::file_time_type mtime{};
        std::optional<double> dpi;
        bool read = false;
    };
    std::mutex design_dpi_mutex_;
    std::map<std::string, DesignDpi> design_dpi_;
};

}  // namespace tilejet::daemon
