// The job store's bookkeeping of tiles on their way to the heads: a send that is taken back
// must leave the tile to be sent again, whatever was sent after it.
#include <catch2/catch.hpp>
#include <filesystem>
#include <random>

#include "../drivers/linesim_process.hpp"
#include "tilejet/jobs/job_store.hpp"
#include "tilejet/jobs/sqlite.hpp"

using namespace tilejet;

TEST_CASE("a tile whose send is taken back is sent again, even after newer tiles went out",
          "[jobs]") {
    test::TempDir dir;
    jobs::JobStore store((dir.path() / "jobs.db").string());
    jobs::JobSpec spec;
    spec.map = "/x.tjmap";
    spec.seed = 1;
    spec.tiles = 5;
    spec.tile_width_mm = spec.tile_height_mm = 100;
    spec.dpi = 20;
    const jobs::Job job = store.add_job(spec);
    using V = std::vector<std::int64_t>;
    REQUIRE(store.upcoming(job, 5) == V{0, 1, 2, 3, 4});

    // 0 and 2 reached the heads; the daemon stopped while sending 1 (a resync found that 1
    // never arrived only after it had probed with 2).
    store.mark_sending(job.id, 0, 1);
    store.mark_sent(job.id, 0);
    store.mark_sending(job.id, 1, 2);
    store.mark_sending(job.id, 2, 3);
    store.mark_sent(job.id, 2);
    store.unmark_sending(job.id, 1);
    CHECK(store.upcoming(job, 5) == V{1, 3, 4});

    // The newest one taken back goes back to pending.
    store.mark_sending(job.id, 3, 4);
    store.unmark_sending(job.id, 3);
    CHECK(store.upcoming(job, 5) == V{1, 3, 4});

    // A blank probe (negative index) taken back leaves nothing to print.
    store.mark_sending(job.id, -9, 5);
    store.unmark_sending(job.id, -9);
    CHECK(store.upcoming(job, 5) == V{1, 3, 4});
}

namespace {

jobs::JobSpec small_spec(int tiles) {
    jobs::JobSpec spec;
    spec.map = "/x.tjmap";
    spec.seed = 1;
    spec.tiles = tiles;
    spec.tile_width_mm = spec.tile_height_mm = 100;
    spec.dpi = 20;
    return spec;
}

struct Counts {
    std::int64_t printed, spoiled, missed;
    bool operator==(const Counts&) const = default;
};

// Counted from the tile rows, as the store did before it kept counters.
Counts counted_rows(const std::filesystem::path& db, std::int64_t job) {
    jobs::Database d(db.string());
    auto s = d.prepare(
        "SELECT (SELECT count(*) FROM tiles WHERE job = ?1 AND state = 'printed' AND idx >= 0), "
        "(SELECT coalesce(sum(spoiled), 0) FROM tiles WHERE job = ?1), "
        "(SELECT coalesce(sum(missed), 0) FROM tiles WHERE job = ?1)");
    s.bind(1, job);
    REQUIRE(s.step());
    return {s.integer(0), s.integer(1), s.integer(2)};
}

}  // namespace

TEST_CASE("a job's printed, spoiled and missed counters always equal its tile rows", "[jobs]") {
    test::TempDir dir;
    const auto path = dir.path() / "jobs.db";
    jobs::JobStore store(path.string());
    const jobs::Job a = store.add_job(small_spec(40)), b = store.add_job(small_spec(40));
    std::mt19937 random(7);
    std::int64_t seq = 0;
    for (int step = 0; step < 3000; ++step) {
        const std::int64_t job = random() % 2 ? a.id : b.id;
        const std::int64_t idx = std::int64_t(random() % 42) - 2;  // blanks are < 0
        switch (random() % 6) {
            case 0:
                store.mark_sending(job, idx, ++seq);
                break;
            case 1:
                store.mark_sent(job, idx);
                break;
            case 2:
                store.mark_printed(job, idx, seq);
                break;
            case 3:
                store.mark_spoiled(job, idx);
                break;
            case 4:
                store.mark_missed(job, idx);
                break;
            default:
                store.unmark_sending(job, idx);
                break;
        }
        if (step % 100 == 0 || step == 2999)
            for (const std::int64_t id : {a.id, b.id}) {
                const jobs::Job j = *store.job(id);
                INFO("step " << step << ", job " << id);
                CHECK(Counts{j.printed, j.spoiled, j.missed} == counted_rows(path, id));
            }
    }
    CHECK(store.job(a.id)->printed > 0);
    CHECK(store.job(a.id)->spoiled > 0);
}

TEST_CASE("a store of schema version 0 is migrated with its counts, a newer one is refused",
          "[jobs]") {
    test::TempDir dir;
    const auto path = dir.path() / "jobs.db";
    std::int64_t id = 0;
    {
        jobs::JobStore store(path.string());
        id = store.add_job(small_spec(10)).id;
        for (std::int64_t i = 0; i < 6; ++i) {
            store.mark_sending(id, i, i + 1);
            store.mark_printed(id, i, i);
        }
        store.mark_spoiled(id, 4);
        store.mark_missed(id, 5);
    }
    {
        // What a store of the last release looked like: no counters, triggers, indexes or map ids;
        // version 0.
        jobs::Database d(path.string());
        d.exec(
            "DROP TRIGGER tiles_counted_insert; DROP TRIGGER tiles_counted_update; "
            "DROP TRIGGER tiles_counted_delete; ALTER TABLE jobs DROP COLUMN printed_count; "
            "ALTER TABLE jobs DROP COLUMN spoiled_count; ALTER TABLE jobs DROP COLUMN "
            "missed_count; ALTER TABLE jobs DROP COLUMN map_id; DROP INDEX tiles_by_job_state; "
            "DROP INDEX tiles_by_seq; PRAGMA user_version = 0");
    }
    {
        jobs::JobStore store(path.string());
        const jobs::Job j = *store.job(id);
        CHECK(Counts{j.printed, j.spoiled, j.missed} == Counts{4, 1, 1});
        CHECK(Counts{j.printed, j.spoiled, j.missed} == counted_rows(path, id));
        store.mark_sending(id, 6, 7);
        store.mark_printed(id, 6, 6);
        CHECK(store.job(id)->printed == 5);
        // Jobs from before ids are not pinned; new ones keep the id they were submitted with.
        CHECK(store.job(id)->spec.map_id.empty());
        jobs::JobSpec pinned = small_spec(3);
        pinned.map_id = std::string(64, 'a');
        CHECK(store.job(store.add_job(pinned).id)->spec.map_id == pinned.map_id);
    }
    {
        jobs::Database d(path.string());
        d.exec("PRAGMA user_version = 99");
    }
    CHECK_THROWS_WITH(jobs::JobStore(path.string()),
                      Catch::Contains("schema version 99") && Catch::Contains(path.string()));
}

// The print loop trusts the heads' print journal only for tiles never spoiled: a spoiled tile's
// first print is in the journal too.
TEST_CASE("a tile's spoils are counted through its reprint", "[jobs]") {
    test::TempDir dir;
    jobs::JobStore store((dir.path() / "jobs.db").string());
    const jobs::Job job = store.add_job(small_spec(3));
    CHECK(store.times_spoiled(job.id, 0) == 0);  // not sent yet
    store.mark_sending(job.id, 0, 1);
    store.mark_sent(job.id, 0);
    store.mark_printed(job.id, 0, 0);
    CHECK(store.times_spoiled(job.id, 0) == 0);
    store.mark_spoiled(job.id, 0);
    store.mark_sending(job.id, 0, 2);  // sent again
    store.mark_sent(job.id, 0);
    CHECK(store.times_spoiled(job.id, 0) == 1);
    CHECK(store.times_spoiled(job.id, 2) == 0);
    CHECK(store.times_spoiled(job.id + 1, 0) == 0);
}
