#include "tilejet/jobs/job.hpp"

#include <array>
#include <utility>

namespace tilejet::jobs {

namespace {

constexpr std::array<std::pair<JobStatus, std::string_view>, 5> kJobStatus{{
    {JobStatus::queued, "queued"},
    {JobStatus::printing, "printing"},
    {JobStatus::done, "done"},
    {JobStatus::cancelled, "cancelled"},
    {JobStatus::failed, "failed"},
}};

constexpr std::array<std::pair<TileState, std::string_view>, 5> kTileState{{
    {TileState::sending, "sending"},
    {TileState::sent, "sent"},
    {TileState::printed, "printed"},
    {TileState::spoiled, "spoiled"},
    {TileState::missed, "missed"},
}};

}  // namespace

std::string_view to_string(JobStatus status) {
    for (const auto& [s, name] : kJobStatus)
        if (s == status) return name;
    return "?";
}

std::optional<JobStatus> parse_job_status(std::string_view text) {
    for (const auto& [s, name] : kJobStatus)
        if (name == text) return s;
    return std::nullopt;
}

std::string_view to_string(TileState state) {
    for (const auto& [s, name] : kTileState)
        if (s == state) return name;
    return "?";
}

std::optional<TileState> parse_tile_state(std::string_view text) {
    for (const auto& [s, name] : kTileState)
        if (name == text) return s;
    return std::nullopt;
}

}  // namespace tilejet::jobs
