#pragma once

// The job store (SQLite, WAL): jobs and the per-tile progress the daemon resumes from after a
// crash or power loss. One JobStore per thread (each has its own connection).
#include <string>
#include <vector>

#include "tilejet/jobs/job.hpp"
#include "tilejet/jobs/sqlite.hpp"

namespace tilejet::jobs {

class JobStore {
  public:
    explicit JobStore(const std::string& path);

    Job add_job(const JobSpec& spec);
    std::optional<Job> job(std::int64_t id);
    std::vector<Job> jobs(int limit = 100);
    // The job the line works on: the oldest printing or queued one.
    std::optional<Job> active_job();
    void set_status(std::int64_t id, JobStatus status, const std::string& message = {});

    // Tiles the heads may hold (sending or sent), oldest send first.
    std::vector<QueuedTile> heads_queue();
    // The next tiles to send, in order: spoiled and missed tiles first (lowest index), then
    // never-sent ones from next_index. At most `count`, never beyond the job's tile count.
    std::vector<std::int64_t> upcoming(const Job& job, int count);

    // Written before the bytes go to the heads; `seq` orders the heads' buffer.
    void mark_sending(std::int64_t job, std::int64_t index, std::int64_t seq);
    void mark_sent(std::int64_t job, std::int64_t index);
    // The send did not happen: the tile is to be sent again.
    void unmark_sending(std::int64_t job, std::int64_t index);
    void mark_printed(std::int64_t job, std::int64_t index, std::int64_t line_tile);
    void mark_spoiled(std::int64_t job, std::int64_t index);
    // It was sent, but the heads lost it before it was printed: it goes out again.
    void mark_missed(std::int64_t job, std::int64_t index);
    void add_missed_line_tiles(std::int64_t job, std::int64_t count);
    std::optional<TileState> tile_state(std::int64_t job, std::int64_t index);
    // How many times the tile was spoiled (printed, then reprinted): 0 for an unknown tile.
    int times_spoiled(std::int64_t job, std::int64_t index);
    // The `limit` highest tile indices of `job` confirmed printed, ascending (the panel's wall).
    std::vector<std::int64_t> printed_tiles(std::int64_t job, int limit);
    // The highest send sequence number in use (0 when none).
    std::int64_t last_seq();

  private:
    Job read_job(Statement& s);
    Database db_;
};

}  // namespace tilejet::jobs
