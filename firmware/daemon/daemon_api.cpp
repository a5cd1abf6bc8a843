#include "daemon_api.hpp"

#include "tile_renderer.hpp"
#include "tilejet/api/job_request.hpp"
#include "tilejet/colour/cmyk_transform.hpp"
#include "tilejet/synth/map_file.hpp"

namespace tilejet::daemon {

DaemonApi::DaemonApi(const DaemonConfig& config, Controller& controller)
    : config_(config), controller_(controller), store_(config.storage.database) {}

nlohmann::json DaemonApi::status() {
    const LineSnapshot s = controller_.snapshot();
    nlohmann::json j{{"state", std::string(to_string(s.status))},
                     {"reason", s.reason},
                     {"link_up", s.link_up},
                     {"estop_latched", s.estop_latched},
                     {"conveyor_running", s.conveyor_running},
                     {"speed_setpoint_mm_s", s.speed_setpoint_mm_s},
                     {"tile_counter", s.tile_counter},
                     {"heads_queue", s.heads_queue},
                     {"rendered_ahead", s.rendered_ahead},
                     {"line_tiles_printed", s.line_tiles_printed},
                     {"line_tiles_missed", s.line_tiles_missed},
                     {"blanks", s.blanks},
                     {"spoiled", s.spoiled},
                     {"previews", config_.storage.previews}};
    if (s.job) {
        std::lock_guard lock(mutex_);
        if (auto job = store_.job(*s.job)) j["job"] = api::job_json(*job);
    }
    return j;
}

nlohmann::json DaemonApi::submit(const jobs::JobSpec& spec) {
    // Rejected here rather than when the line reaches the job: a queue must not stall on a
    // job that can never print.
    try {
        synth::load_texture_map(spec.map);
    } catch (const std::exception& e) {
        throw api::ApiError(400, "map", std::string("map: ") + e.what());
    }
    try {
        colour::CmykTransform transform(job_colour(spec, config_.colour));
    } catch (const std::exception& e) {
        throw api::ApiError(400, "profile", std::string("profile: ") + e.what());
    }
    std::lock_guard lock(mutex_);
    return api::job_json(store_.add_job(spec));
}

nlohmann::json DaemonApi::jobs() {
    std::lock_guard lock(mutex_);
    nlohmann::json list = nlohmann::json::array();
    for (const jobs::Job& j : store_.jobs())
        list.push_back(api::job_json(j));
    return list;
}

std::optional<nlohmann::json> DaemonApi::job(std::int64_t id) {
    std::lock_guard lock(mutex_);
    auto j = store_.job(id);
    if (!j) return std::nullopt;
    return api::job_json(*j);
}

nlohmann::json DaemonApi::command(std::string_view name) {
    if (name == "pause")
        controller_.post(Command::pause);
    else if (name == "resume")
        controller_.post(Command::resume);
    else if (name == "stop")
        controller_.post(Command::stop_job);
    else if (name == "acknowledge")
        controller_.post(Command::acknowledge);
    else
        throw api::ApiError(404, "command", "no command '" + std::string(name) + "'");
    return {{"accepted", std::string(name)}};
}

}  // namespace tilejet::daemon
