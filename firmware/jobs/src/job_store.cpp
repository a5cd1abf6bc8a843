#include "tilejet/jobs/job_store.hpp"

#include <algorithm>
#include <stdexcept>

namespace tilejet::jobs {

namespace {

constexpr std::string_view kSchema = R"(
CREATE TABLE IF NOT EXISTS jobs (
    id INTEGER PRIMARY KEY AUTOINCREMENT,
    map TEXT NOT NULL,
    profile TEXT NOT NULL,
    seed TEXT NOT NULL,
    tiles INTEGER NOT NULL,
    tile_width_mm REAL NOT NULL,
    tile_height_mm REAL NOT NULL,
    dpi INTEGER NOT NULL,
    layout TEXT NOT NULL,
    wall_width INTEGER NOT NULL,
    status TEXT NOT NULL,
    message TEXT NOT NULL DEFAULT '',
    next_index INTEGER NOT NULL DEFAULT 0,
    missed_line_tiles INTEGER NOT NULL DEFAULT 0,
    created TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ','now')),
    started TEXT NOT NULL DEFAULT '',
    finished TEXT NOT NULL DEFAULT ''
);
CREATE TABLE IF NOT EXISTS tiles (
    job INTEGER NOT NULL REFERENCES jobs(id),
    idx INTEGER NOT NULL,
    state TEXT NOT NULL,
    seq INTEGER NOT NULL DEFAULT 0,
    line_tile INTEGER,
    spoiled INTEGER NOT NULL DEFAULT 0,
    missed INTEGER NOT NULL DEFAULT 0,
    PRIMARY KEY (job, idx)
);
CREATE INDEX IF NOT EXISTS tiles_by_state ON tiles(state, seq);
)";

// Version 2: each job keeps its printed, spoiled and missed counts as columns, which triggers
// change in the same statement (and so the same transaction) as the tile rows they count.
// Counting the rows instead took 4 ms a turn at 10 000 printed tiles and 64 ms at 200 000.
constexpr int kSchemaVersion = 2;
// With them, the queries a turn makes find their rows by index whatever the job's size: the
// tiles to print again (upcoming) and the highest sequence number (last_seq, at start-up).
constexpr std::string_view kCounters = R"(
CREATE INDEX IF NOT EXISTS tiles_by_job_state ON tiles(job, state, idx);
CREATE INDEX IF NOT EXISTS tiles_by_seq ON tiles(seq);
CREATE TRIGGER IF NOT EXISTS tiles_counted_insert AFTER INSERT ON tiles BEGIN
    UPDATE jobs SET
        printed_count = printed_count + (NEW.state = 'printed' AND NEW.idx >= 0),
        spoiled_count = spoiled_count + NEW.spoiled,
        missed_count = missed_count + NEW.missed
    WHERE id = NEW.job;
END;
CREATE TRIGGER IF NOT EXISTS tiles_counted_update AFTER UPDATE ON tiles BEGIN
    UPDATE jobs SET
        printed_count = printed_count + (NEW.state = 'printed' AND NEW.idx >= 0)
                                      - (OLD.state = 'printed' AND OLD.idx >= 0),
        spoiled_count = spoiled_count + NEW.spoiled - OLD.spoiled,
        missed_count = missed_count + NEW.missed - OLD.missed
    WHERE id = NEW.job;
END;
CREATE TRIGGER IF NOT EXISTS tiles_counted_delete AFTER DELETE ON tiles BEGIN
    UPDATE jobs SET
        printed_count = printed_count - (OLD.state = 'printed' AND OLD.idx >= 0),
        spoiled_count = spoiled_count - OLD.spoiled,
        missed_count = missed_count - OLD.missed
    WHERE id = OLD.job;
END;
)";

constexpr std::string_view kJobColumns =
    "SELECT id, map, profile, seed, tiles, tile_width_mm, tile_height_mm, dpi, layout, "
    "wall_width, status, message, next_index, missed_line_tiles, created, started, finished, "
    "printed_count, spoiled_count, missed_count, map_id FROM jobs ";

bool has_column(Database& db, const char* table, std::string_view column) {
    bool found = false;
    for (auto s = db.prepare(std::string("SELECT name FROM pragma_table_info('") + table + "')");
         s.step();)
        found |= s.text(0) == column;
    return found;
}

}  // namespace

JobStore::JobStore(const std::string& path) : db_(path) {
    // Migrated in one write transaction: a crash half way leaves the old store as it was, and
    // the API's store and the print loop's, opened together, migrate one after the other.
    Transaction t(db_);
    std::int64_t found = 0;
    {
        auto version = db_.prepare("PRAGMA user_version");
        if (version.step()) found = version.integer(0);
    }
    if (found > kSchemaVersion)
        throw StoreError("job store " + path + " has schema version " + std::to_string(found) +
                         ", newer than this daemon's " + std::to_string(kSchemaVersion) +
                         ": update the daemon");
    if (found == kSchemaVersion) {
        t.commit();
        return;
    }
    db_.exec(kSchema);
    // Stores made before tiles.missed existed get the column (CREATE TABLE IF NOT EXISTS
    // leaves an old table as it was).
    if (!has_column(db_, "tiles", "missed"))
        db_.exec("ALTER TABLE tiles ADD COLUMN missed INTEGER NOT NULL DEFAULT 0");
    for (const char* column : {"printed_count", "spoiled_count", "missed_count"})
        if (!has_column(db_, "jobs", column))
            db_.exec(std::string("ALTER TABLE jobs ADD COLUMN ") + column +
                     " INTEGER NOT NULL DEFAULT 0");
    if (!has_column(db_, "jobs", "map_id"))
        db_.exec("ALTER TABLE jobs ADD COLUMN map_id TEXT NOT NULL DEFAULT ''");
    // Counted once from the rows; from here on the triggers keep them.
    db_.exec(
        "UPDATE jobs SET "
        "printed_count = (SELECT count(*) FROM tiles t WHERE t.job = jobs.id AND "
        "t.state = 'printed' AND t.idx >= 0), "
        "spoiled_count = (SELECT coalesce(sum(spoiled), 0) FROM tiles t WHERE t.job = jobs.id), "
        "missed_count = (SELECT coalesce(sum(missed), 0) FROM tiles t WHERE t.job = jobs.id)");
    db_.exec(kCounters);
    db_.exec("PRAGMA user_version = " + std::to_string(kSchemaVersion));
    t.commit();
}

Job JobStore::read_job(Statement& s) {
    Job j;
    j.id = s.integer(0);
    j.spec.map = s.text(1);
    j.spec.profile = s.text(2);
    j.spec.seed = std::stoull(s.text(3));
    j.spec.tiles = s.integer(4);
    j.spec.tile_width_mm = s.real(5);
    j.spec.tile_height_mm = s.real(6);
    j.spec.dpi = int(s.integer(7));
    j.spec.layout = s.text(8);
    j.spec.wall_width = int(s.integer(9));
    j.status = parse_job_status(s.text(10)).value_or(JobStatus::failed);
    j.message = s.text(11);
    j.next_index = s.integer(12);
    j.missed_line_tiles = s.integer(13);
    j.created = s.text(14);
    j.started = s.text(15);
    j.finished = s.text(16);
    j.printed = s.integer(17);
    j.spoiled = s.integer(18);
    j.missed = s.integer(19);
    j.spec.map_id = s.text(20);
    return j;
}

Job JobStore::add_job(const JobSpec& spec) {
    auto s = db_.prepare(
        "INSERT INTO jobs (map, profile, seed, tiles, tile_width_mm, tile_height_mm, dpi, layout, "
        "wall_width, status, map_id) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, 'queued', ?)");
    s.bind(1, spec.map)
        .bind(2, spec.profile)
        .bind(3, std::to_string(spec.seed))
        .bind(4, std::int64_t(spec.tiles))
        .bind(5, spec.tile_width_mm)
        .bind(6, spec.tile_height_mm)
        .bind(7, std::int64_t(spec.dpi))
        .bind(8, spec.layout)
        .bind(9, std::int64_t(spec.wall_width))
        .bind(10, spec.map_id)
        .run();
    return *job(db_.last_insert_rowid());
}

std::optional<Job> JobStore::job(std::int64_t id) {
    auto s = db_.prepare(std::string(kJobColumns) + "WHERE id = ?");
    s.bind(1, id);
    if (!s.step()) return std::nullopt;
    return read_job(s);
}

std::vector<Job> JobStore::jobs(int limit) {
    auto s = db_.prepare(std::string(kJobColumns) + "ORDER BY id DESC LIMIT ?");
    s.bind(1, std::int64_t(limit));
    std::vector<Job> out;
    while (s.step())
        out.push_back(read_job(s));
    return out;
}

std::optional<Job> JobStore::active_job() {
    auto s = db_.prepare(std::string(kJobColumns) +
                         "WHERE status IN ('printing', 'queued') ORDER BY id LIMIT 1");
    if (!s.step()) return std::nullopt;
    return read_job(s);
}

void JobStore::set_status(std::int64_t id, JobStatus status, const std::string& message) {
    const char* sql =
        "UPDATE jobs SET status = ?2, message = ?3, "
        "started = CASE WHEN ?2 = 'printing' AND started = '' "
        "  THEN strftime('%Y-%m-%dT%H:%M:%fZ','now') ELSE started END, "
        "finished = CASE WHEN ?2 IN ('done', 'cancelled', 'failed') "
        "  THEN strftime('%Y-%m-%dT%H:%M:%fZ','now') ELSE finished END WHERE id = ?1";
    db_.prepare(sql)
        .bind(1, id)
        .bind(2, to_string(status))
        .bind(3, std::string_view(message))
        .run();
}

std::vector<QueuedTile> JobStore::heads_queue() {
    auto s = db_.prepare(
        "SELECT job, idx, state, seq FROM tiles WHERE state IN ('sending', 'sent') ORDER BY seq");
    std::vector<QueuedTile> out;
    while (s.step())
        out.push_back({s.integer(0), s.integer(1),
                       parse_tile_state(s.text(2)).value_or(TileState::sent), s.integer(3)});
    return out;
}

std::vector<std::int64_t> JobStore::upcoming(const Job& job, int count) {
    // One index range per state, merged here: with `state IN (...)` SQLite walked the job's
    // rows in index order instead, every row of a job of a million tiles, every turn.
    std::vector<std::int64_t> out;
    for (const char* state : {"spoiled", "missed"}) {
        auto s =
            db_.prepare("SELECT idx FROM tiles WHERE job = ? AND state = ? ORDER BY idx LIMIT ?");
        s.bind(1, job.id).bind(2, std::string_view(state)).bind(3, std::int64_t(count));
        while (s.step())
            out.push_back(s.integer(0));
    }
    std::sort(out.begin(), out.end());
    if (int(out.size()) > count) out.resize(size_t(count));
    auto n = db_.prepare("SELECT next_index FROM jobs WHERE id = ?");
    n.bind(1, job.id);
    std::int64_t next = n.step() ? n.integer(0) : job.spec.tiles;
    while (int(out.size()) < count && next < job.spec.tiles)
        out.push_back(next++);
    return out;
}

void JobStore::mark_sending(std::int64_t job, std::int64_t index, std::int64_t seq) {
    Transaction t(db_);
    db_.prepare(
           "INSERT INTO tiles (job, idx, state, seq) VALUES (?1, ?2, 'sending', ?3) "
           "ON CONFLICT (job, idx) DO UPDATE SET state = 'sending', seq = ?3")
        .bind(1, job)
        .bind(2, index)
        .bind(3, seq)
        .run();
    db_.prepare("UPDATE jobs SET next_index = max(next_index, ?2 + 1) WHERE id = ?1")
        .bind(1, job)
        .bind(2, index)
        .run();
    t.commit();
}

void JobStore::mark_sent(std::int64_t job, std::int64_t index) {
    db_.prepare("UPDATE tiles SET state = 'sent' WHERE job = ? AND idx = ?")
        .bind(1, job)
        .bind(2, index)
        .run();
}

void JobStore::unmark_sending(std::int64_t job, std::int64_t index) {
    // A tile that was spoiled or missed before keeps that state and is sent again. A fresh one
    // goes back to pending when it is the newest (next_index moves back to it); an older one,
    // whose newer neighbours already went out (a resync sends probes before it learns that
    // this tile never arrived), waits as missed, since next_index cannot reach it any more.
    // A blank probe's row (index < 0) is simply dropped.
    Transaction t(db_);
    const auto run = [&](const char* sql) { db_.prepare(sql).bind(1, job).bind(2, index).run(); };
    run("UPDATE tiles SET state = CASE WHEN spoiled > 0 THEN 'spoiled' ELSE 'missed' END "
        "WHERE job = ?1 AND idx = ?2 AND state = 'sending' AND (spoiled > 0 OR missed > 0)");
    run("UPDATE jobs SET next_index = ?2 WHERE id = ?1 AND next_index = ?2 + 1 AND EXISTS "
        "(SELECT 1 FROM tiles WHERE job = ?1 AND idx = ?2 AND state = 'sending')");
    run("DELETE FROM tiles WHERE job = ?1 AND idx = ?2 AND state = 'sending' AND "
        "(?2 < 0 OR ?2 = (SELECT next_index FROM jobs WHERE id = ?1))");
    run("UPDATE tiles SET state = 'missed' WHERE job = ?1 AND idx = ?2 AND state = 'sending'");
    t.commit();
}

void JobStore::mark_printed(std::int64_t job, std::int64_t index, std::int64_t line_tile) {
    auto s =
        db_.prepare("UPDATE tiles SET state = 'printed', line_tile = ? WHERE job = ? AND idx = ?");
    if (line_tile < 0)
        s.bind_null(1);
    else
        s.bind(1, line_tile);
    s.bind(2, job).bind(3, index).run();
}

void JobStore::mark_spoiled(std::int64_t job, std::int64_t index) {
    db_.prepare(
           "UPDATE tiles SET state = 'spoiled', spoiled = spoiled + 1 WHERE job = ? AND idx = ?")
        .bind(1, job)
        .bind(2, index)
        .run();
}

void JobStore::mark_missed(std::int64_t job, std::int64_t index) {
    db_.prepare("UPDATE tiles SET state = 'missed', missed = missed + 1 WHERE job = ? AND idx = ?")
        .bind(1, job)
        .bind(2, index)
        .run();
}

void JobStore::add_missed_line_tiles(std::int64_t job, std::int64_t count) {
    db_.prepare("UPDATE jobs SET missed_line_tiles = missed_line_tiles + ? WHERE id = ?")
        .bind(1, count)
        .bind(2, job)
        .run();
}

std::optional<TileState> JobStore::tile_state(std::int64_t job, std::int64_t index) {
    auto s = db_.prepare("SELECT state FROM tiles WHERE job = ? AND idx = ?");
    s.bind(1, job).bind(2, index);
    if (!s.step()) return std::nullopt;
    return parse_tile_state(s.text(0));
}

int JobStore::times_spoiled(std::int64_t job, std::int64_t index) {
    auto s = db_.prepare("SELECT spoiled FROM tiles WHERE job = ? AND idx = ?");
    s.bind(1, job).bind(2, index);
    return s.step() ? int(s.integer(0)) : 0;
}

std::int64_t JobStore::last_seq() {
    auto s = db_.prepare("SELECT coalesce(max(seq), 0) FROM tiles");
    return s.step() ? s.integer(0) : 0;
}

std::vector<std::int64_t> JobStore::printed_tiles(std::int64_t job, int limit) {
    auto s = db_.prepare(
        "SELECT idx FROM tiles WHERE job = ? AND state = 'printed' ORDER BY idx DESC LIMIT ?");
    s.bind(1, job).bind(2, std::int64_t(limit));
    std::vector<std::int64_t> out;
    while (s.step())
        out.push_back(s.integer(0));
    std::reverse(out.begin(), out.end());
    return out;
}

}  // namespace tilejet::jobs
