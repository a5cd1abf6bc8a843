#pragma once

// A print job and the state of its tiles, as the job store keeps them.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace tilejet::jobs {

// What the operator asks for (tilejet job submit, POST /api/jobs).
struct JobSpec {
    std::string map;  // texture map file (absolute)
    // The map's content id (hex) when the job was submitted: the job prints that design or
    // nothing, even if the file is replaced before it resumes. Empty: jobs from before ids.
    std::string map_id;
    std::string profile;  // CMYK output profile; empty: [colour] output_profile
    std::uint64_t seed = 0;
    std::int64_t tiles = 0;
    double tile_width_mm = 0, tile_height_mm = 0;
    int dpi = 0;
    std::string layout = "scatter";  // scatter | wall
    int wall_width = 10;
};

enum class JobStatus { queued, printing, done, cancelled, failed };
std::string_view to_string(JobStatus status);
std::optional<JobStatus> parse_job_status(std::string_view text);

struct Job {
    std::int64_t id = 0;
    JobSpec spec;
    JobStatus status = JobStatus::queued;
    std::string message;                     // why it failed or was cancelled
    std::int64_t next_index = 0;             // the first tile index never sent to the heads
    std::int64_t printed = 0;                // tiles confirmed printed (each index counts once)
    std::int64_t spoiled = 0;                // times a tile was spoiled (e-stop under the heads)
    std::int64_t missed = 0;                 // times the heads lost a sent tile unprinted
    std::int64_t missed_line_tiles = 0;      // tiles of the line that passed the heads unprinted
    std::string created, started, finished;  // ISO 8601 UTC, empty until it happens

    // The heads' name for it: no whitespace (it travels in a line protocol).
    std::string name() const { return "job-" + std::to_string(id); }
};

// A tile of a job on its way to the heads. A tile index with no row is pending.
//   sending  the daemon is about to hand it to the heads (written before the send)
//   sent     the heads hold its separations
//   printed  the line confirmed it (tile counter passed with print-enable on)
//   spoiled  it was under the heads when an e-stop hit: printed again, same index and bytes
//   missed   lost on its way (heads lost their buffer): printed again
enum class TileState { sending, sent, printed, spoiled, missed };
std::string_view to_string(TileState state);
std::optional<TileState> parse_tile_state(std::string_view text);

// A tile the heads may hold, in the order it was sent.
struct QueuedTile {
    std::int64_t job = 0;
    std::int64_t index = 0;
    TileState state = TileState::sent;
    std::int64_t seq = 0;
};

}  // namespace tilejet::jobs
