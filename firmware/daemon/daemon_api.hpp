#pragma once

// DaemonApi: the API's view of the daemon: the job store (its own connection) for jobs, the
// controller for state and commands.
#include <mutex>

#include "controller.hpp"
#include "daemon_config.hpp"
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
    int default_dpi() const override { return config_.render.dpi; }

  private:
    DaemonConfig config_;
    Controller& controller_;
    std::mutex mutex_;
    jobs::JobStore store_;
};

}  // namespace tilejet::daemon
