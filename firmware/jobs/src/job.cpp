#include "tilejet/jobs/job.hpp"

#include "tilejet/config/enum_names.hpp"

namespace tilejet::jobs {

namespace {

constexpr config::EnumNames kJobStatus{std::array<std::pair<JobStatus, std::string_view>, 5>{{
    {JobStatus::queued, "queued"},
    {JobStatus::printing, "printing"},
    {JobStatus::done, "done"},
    {JobStatus::cancelled, "cancelled"},
    {JobStatus::failed, "failed"},
}}};

constexpr config::EnumNames kTileState{std::array<std::pair<TileState, std::string_view>, 5>{{
    {TileState::sending, "sending"},
    {TileState::sent, "sent"},
    {TileState::printed, "printed"},
    {TileState::spoiled, "spoiled"},
    {TileState::missed, "missed"},
}}};

}  // namespace

std::string_view to_string(JobStatus status) {
    return kJobStatus.name(status);
}

std::optional<JobStatus> parse_job_status(std::string_view text) {
    return kJobStatus.parse(text);
}

std::string_view to_string(TileState state) {
    return kTileState.name(state);
}

std::optional<TileState> parse_tile_state(std::string_view text) {
    return kTileState.parse(text);
}

}  // namespace tilejet::jobs
