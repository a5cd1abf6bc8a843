// The job store's cost per print-loop turn as a job grows: the reads every turn makes (the
// job's counters, the next tiles to render), one tile's writes on its way to the heads, and a
// restart's reads, at 0 to 1 000 000 tile rows. Beside them, in the same run, the baseline:
// counting the job's printed tiles from its rows, as the store did before it kept counters.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "tilejet/jobs/job_store.hpp"
#include "tilejet/jobs/sqlite.hpp"

using namespace tilejet;
using Clock = std::chrono::steady_clock;

namespace {

double us_since(Clock::time_point t0, int repeats = 1) {
    return std::chrono::duration<double, std::micro>(Clock::now() - t0).count() / repeats;
}

struct Figures {
    double turn_us, tile_us, baseline_us, restart_ms;
};

Figures measure(const std::filesystem::path& dir, std::int64_t rows, int repeats) {
    const auto path = (dir / ("store-" + std::to_string(rows) + ".db")).string();
    std::int64_t id = 0;
    {
        jobs::JobStore store(path);
        jobs::JobSpec spec;
        spec.map = "/bench.tjmap";
        spec.seed = 1;
        spec.tiles = int(rows + 100000);
        spec.tile_width_mm = spec.tile_height_mm = 600;
        spec.dpi = 360;
        id = store.add_job(spec).id;
    }
    {
        // The job's first `rows` tiles, printed, written as the loop would leave them.
        jobs::Database db(path);
        jobs::Transaction t(db);
        auto insert = db.prepare(
            "INSERT INTO tiles (job, idx, state, seq, line_tile) VALUES (?1, ?2, 'printed', ?2 + "
            "1, "
            "?2)");
        for (std::int64_t i = 0; i < rows; ++i)
            insert.bind(1, id).bind(2, i).run(), insert.reset();
        db.prepare("UPDATE jobs SET next_index = ?2, status = 'printing' WHERE id = ?1")
            .bind(1, id)
            .bind(2, rows)
            .run();
        t.commit();
    }
    Figures f{};
    auto t0 = Clock::now();
    jobs::JobStore store(path);
    const auto job = store.active_job();
    store.heads_queue();
    std::int64_t seq = store.last_seq();
    store.upcoming(*job, 8);
    f.restart_ms = us_since(t0) / 1000;

    t0 = Clock::now();
    for (int r = 0; r < repeats; ++r) {
        const auto j = store.job(id);
        store.upcoming(*j, 8);
    }
    f.turn_us = us_since(t0, repeats);

    t0 = Clock::now();
    for (int r = 0; r < repeats; ++r) {
        const std::int64_t idx = rows + r;
        store.mark_sending(id, idx, ++seq);
        store.mark_sent(id, idx);
        store.mark_printed(id, idx, idx);
    }
    f.tile_us = us_since(t0, repeats);

    jobs::Database db(path);
    auto count =
        db.prepare("SELECT count(*) FROM tiles WHERE job = ? AND state = 'printed' AND idx >= 0");
    t0 = Clock::now();
    for (int r = 0; r < repeats; ++r) {
        count.bind(1, id);
        count.step();
        count.reset();
    }
    f.baseline_us = us_since(t0, repeats);
    return f;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"tilejet-store-bench: the job store's cost per print-loop turn as a job grows"};
    bool smoke = false;
    app.add_flag("--smoke", smoke, "small stores only (checks that it runs)");
    CLI11_PARSE(app, argc, argv);
    try {
        std::string pattern = (std::filesystem::temp_directory_path() / "tjstore-XXXXXX").string();
        if (!mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
        const std::filesystem::path dir = pattern;
        std::printf("job store per print-loop turn (file-backed SQLite, WAL, synchronous=FULL)\n");
        std::printf("  %10s %14s %16s %14s %22s\n", "tile rows", "turn reads us",
                    "one tile's writes", "restart ms", "baseline: count rows us");
        for (const std::int64_t rows : smoke
                                           ? std::vector<std::int64_t>{0, 1000}
                                           : std::vector<std::int64_t>{0, 10000, 100000, 1000000}) {
            const Figures f = measure(dir, rows, smoke ? 20 : 1000);
            std::printf("  %10lld %14.1f %14.0f us %14.1f %22.1f\n", (long long)rows, f.turn_us,
                        f.tile_us, f.restart_ms, f.baseline_us);
            std::fflush(stdout);
        }
        std::filesystem::remove_all(dir);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tilejet-store-bench: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
