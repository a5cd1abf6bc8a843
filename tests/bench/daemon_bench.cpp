// tilejet-daemon-bench: how fast the daemon prints 600 x 600 mm tiles at 360 dpi (8504 px square,
// 72.3 Mpx, 289 MB of CMYK each).
//  1. The render path alone (TileRenderer, as render-ahead runs it), beside memcpy of the same
//     bytes on the same machine, against the need of a 1200 mm line at 50 m/min (200 Mpx/s) and
//     the target of 5x that (1 Gpx/s).
//  2. tilejetd on tilejet-linesim at increasing conveyor speeds: tiles/min and Mpx/s it sustains,
//     whether it had to slow the conveyor, line tiles that passed unprinted, and its peak memory.
//     --no-head-checksums: the simulated heads count the bytes without hashing them, so that on a
//     small machine the test rig's SHA-256 does not take the cores the daemon is measured on.
// Prints figures; never passes or fails on them. --smoke: tiny tiles, one speed (CTest).
#include <sys/resource.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstring>

#include "../firmware/daemon_process.hpp"
#include "tile_renderer.hpp"

using namespace tilejet;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

long peak_rss_mb(pid_t pid) {
    std::ifstream in("/proc/" + std::to_string(pid) + "/status");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("VmHWM:", 0) == 0) return std::stol(line.substr(6)) / 1024;
    return -1;
}

// The small demo map built for `dpi` (tests/CMakeLists.txt): a job prints a design at the
// resolution its map is built for.
std::string map_at(int dpi) {
    return std::string(TILEJET_TEST_MAP_DIR) + "/small-" + std::to_string(dpi) + ".tjmap";
}

void render_path(double tile_mm, int dpi, int tiles) {
    jobs::Job job;
    job.id = 1;
    job.spec.map = map_at(dpi);
    job.spec.seed = 7;
    job.spec.tiles = tiles;
    job.spec.tile_width_mm = job.spec.tile_height_mm = tile_mm;
    job.spec.dpi = dpi;
    colour::ColourSettings colour;
    colour.output_profile = TILEJET_TEST_CMYK_PROFILE;
    const daemon::TileRenderer renderer(job, colour);
    const int threads = int(std::thread::hardware_concurrency());
    const auto g = renderer.geometry();
    const double mpx = double(g.width) * g.height / 1e6;
    std::printf("render path: %d x %d px tiles (%.1f Mpx, %.0f MB CMYK), %d threads\n", g.width,
                g.height, mpx, mpx * 4, threads);

    // As render-ahead does: each tile into the bytes of one already sent.
    daemon::Separations tile = renderer.render(0, threads);  // first touch of the map's pages
    auto t0 = Clock::now();
    std::size_t check = 0;
    for (int k = 1; k <= tiles; ++k) {
        tile = renderer.render(k, threads, std::move(tile.bytes));
        check += tile.bytes[std::size_t(k)];
    }
    const double render_s = seconds_since(t0) / tiles;
    // Each tile into fresh memory: what render-ahead did before it recycled buffers.
    t0 = Clock::now();
    for (int k = 1; k <= tiles; ++k)
        check += renderer.render(k, threads).bytes[std::size_t(k)];
    const double fresh_s = seconds_since(t0) / tiles;

    const std::size_t bytes = std::size_t(g.width) * std::size_t(g.height) * 4;
    std::vector<std::uint8_t> from(bytes, 1), to(bytes);
    std::memcpy(to.data(), from.data(), bytes);
    t0 = Clock::now();
    for (int k = 0; k < tiles; ++k) {
        from[std::size_t(k)] = std::uint8_t(k);
        std::memcpy(to.data(), from.data(), bytes);
        check += to[std::size_t(k)];
    }
    const double copy_s = seconds_since(t0) / tiles;
    std::printf("  %-34s %8.1f ms/tile %8.0f Mpx/s %6.2f GB/s\n",
                "tile render (CMYK), reused bytes", render_s * 1e3, mpx / render_s,
                bytes / render_s / 1e9);
    std::printf("  %-34s %8.1f ms/tile %8.0f Mpx/s %6.2f GB/s\n",
                "same, into fresh memory each tile", fresh_s * 1e3, mpx / fresh_s,
                bytes / fresh_s / 1e9);
    std::printf("  %-34s %8.1f ms/tile %8.0f Mpx/s %6.2f GB/s\n", "baseline: memcpy, 1 thread",
                copy_s * 1e3, mpx / copy_s, bytes / copy_s / 1e9);
    std::printf("  need 200 Mpx/s (1200 mm at 50 m/min): %.1fx; target 1000 Mpx/s: %.2fx\n",
                mpx / render_s / 200, mpx / render_s / 1000);
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    std::printf("  peak memory of this process: %ld MB (checksum %zu)\n", usage.ru_maxrss / 1024,
                check);
}

void on_the_line(double tile_mm, int dpi, const std::vector<int>& speeds, int tiles,
                 bool head_checksums) {
    std::printf(
        "\non the simulated line: %.0f mm tiles at %d dpi, pitch %.0f mm, %d per speed; "
        "heads %s\n",
        tile_mm, dpi, tile_mm + 50, tiles,
        head_checksums ? "SHA-256 every tile" : "count the bytes, no SHA-256");
    std::printf("  %8s %10s %10s %10s %10s %8s %8s %8s %9s\n", "mm/s", "need t/min", "got t/min",
                "need Mpx/s", "got Mpx/s", "slowed", "passed", "late", "peak MB");
    // The shipped register map says the PLC goes up to 2000 mm/s; this line is a faster one.
    test::TempDir maps;
    const std::string registers = (maps.path() / "registers.toml").string();
    {
        std::ifstream in(TILEJET_SOURCE_DIR "/config/registers.toml");
        std::stringstream text;
        text << in.rdbuf();
        std::string map = text.str();
        const std::string limit = "max = 2000";
        if (map.find(limit) == std::string::npos)
            throw std::runtime_error("registers.toml: speed_setpoint's max moved");
        map.replace(map.find(limit), limit.size(), "max = 60000");
        std::ofstream(registers) << map;
    }
    const double px = std::round(tile_mm / 25.4 * dpi);
    const double mpx = px * px / 1e6;
    for (int speed : speeds) {
        test::LinesimOptions lo;
        lo.speed_mm_s = speed;
        lo.tile_length_mm = tile_mm;
        lo.tile_pitch_mm = tile_mm + 50;
        lo.photo_eye_mm = 50;
        lo.heads_mm = tile_mm + 100;
        lo.register_map = registers;
        lo.head_checksums = head_checksums;
        test::LinesimProcess line(lo);
        test::TempDir dir;
        test::DaemonOptions d;
        d.speed_mm_s = speed;
        d.min_speed_mm_s = std::min(100, speed);
        d.render_threads = 0;
        d.queue_tiles = 4;
        test::DaemonProcess daemon(line, dir.path(), d);
        const auto [status, body] = daemon.request(
            "POST", "/api/jobs",
            R"({"map":")" + daemon.add_design(map_at(dpi)) + R"(","seed":11,"tiles":)" +
                std::to_string(tiles) + R"(,"tile_mm":")" + std::to_string(int(tile_mm)) + "x" +
                std::to_string(int(tile_mm)) + R"(","dpi":)" + std::to_string(dpi) + "}");
        if (status != 201) throw std::runtime_error("job refused: " + body.dump());
        const auto id = body.at("id").get<std::int64_t>();
        std::optional<Clock::time_point> first;
        Clock::time_point last{};
        int slowest = speed;
        long peak = 0;
        nlohmann::json job;
        const auto give_up = Clock::now() + std::chrono::seconds(30 + tiles * 10);
        while (Clock::now() < give_up) {
            job = daemon.job(id);
            const int printed = job.value("printed", 0);
            if (printed >= 1 && !first) first = Clock::now();
            if (printed >= tiles && last == Clock::time_point{}) last = Clock::now();
            if (job.value("status", "") == "done") break;
            slowest = std::min(slowest, line.status().value("speed_setpoint", speed));
            peak = std::max(peak, peak_rss_mb(daemon.pid()));
            std::this_thread::sleep_for(20ms);
        }
        peak = std::max(peak, peak_rss_mb(daemon.pid()));
        if (job.value("status", "") != "done" || !first) {
            std::printf("  %8d  did not finish: %s\n", speed, job.dump().c_str());
            continue;
        }
        const double per_min =
            (tiles - 1) / std::chrono::duration<double>(last - *first).count() * 60;
        const double need = speed / (tile_mm + 50) * 60;
        // Sends that ended too close to a tile's arrival: each stops the conveyor for a resync.
        int late = 0;
        const std::string log = daemon.log();
        for (auto at = log.find("too close"); at != std::string::npos;
             at = log.find("too close", at + 1))
            ++late;
        std::printf("  %8d %10.1f %10.1f %10.0f %10.0f %8s %8lld %8d %9ld\n", speed, need, per_min,
                    need / 60 * mpx, per_min / 60 * mpx, slowest < speed ? "yes" : "no",
                    static_cast<long long>(job.value("missed_line_tiles", 0)), late, peak);
        // Why it had to slow down or stop, as the daemon says it (the first few times).
        std::istringstream lines(log);
        int shown = 0;
        for (std::string line; std::getline(lines, line) && shown < 3;)
            if (line.find("passed with no separations ready: conveyor slowed") !=
                    std::string::npos ||
                line.find("too close") != std::string::npos)
                std::printf("           %s\n", line.c_str()), ++shown;
        std::fflush(stdout);
    }
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"tilejet-daemon-bench: the daemon's sustained print rate"};
    bool smoke = false, no_head_checksums = false;
    int tiles = 12;
    std::vector<int> speeds{500, 1000, 2000, 3000, 4000};
    app.add_flag("--smoke", smoke, "tiny tiles, one speed (checks that it runs)");
    app.add_option("--tiles", tiles, "tiles per measurement")->check(CLI::Range(2, 1000));
    app.add_option("--speeds", speeds, "conveyor speeds in mm/s");
    app.add_flag("--no-head-checksums", no_head_checksums,
                 "simulated heads skip the SHA-256 (it takes a core at ~5 tiles/s)");
    CLI11_PARSE(app, argc, argv);
    try {
        if (smoke) {
            render_path(100, 36, 2);
            on_the_line(100, 36, {1000}, 4, true);
        } else {
            render_path(600, 360, 4);
            on_the_line(600, 360, speeds, tiles, !no_head_checksums);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tilejet-daemon-bench: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
