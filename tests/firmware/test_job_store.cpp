// The job store's bookkeeping of tiles on their way to the heads: a send that is taken back
// must leave the tile to be sent again, whatever was sent after it.
#include <catch2/catch.hpp>

#include "../drivers/linesim_process.hpp"
#include "tilejet/jobs/job_store.hpp"

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
