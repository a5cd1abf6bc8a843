// tilejetd against tilejet-linesim, both as separate processes on loopback: a job prints every
// tile exactly once with the bytes an offline render gives, through SIGKILL and restart, an
// e-stop and a Modbus link drop.
#include <catch2/catch.hpp>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <random>

#include "daemon_process.hpp"
#include "print_log_check.hpp"

using namespace tilejet;
using namespace std::chrono_literals;
using nlohmann::json;

namespace {

constexpr int kSide = 157;  // 200 mm at 20 dpi
std::string job_body(const test::DaemonProcess& d, int tiles) {
    return R"({"map":")" + d.add_design(TILEJET_TEST_MAP) + R"(","seed":4242,"tiles":)" +
           std::to_string(tiles) + R"(,"tile_mm":"200x200","dpi":20})";
}

// The separations' SHA-256 per tile, rendered offline.
std::vector<std::string> reference_hashes(int tiles) {
    static const test::ReferenceRenderer renderer(TILEJET_TEST_MAP, TILEJET_TEST_CMYK_PROFILE,
                                                  kSide);
    std::vector<std::string> hashes;
    for (int k = 0; k < tiles; ++k)
        hashes.push_back(renderer.hash(4242, std::uint64_t(k)));
    return hashes;
}

std::int64_t submit(const test::DaemonProcess& d, int tiles) {
    const auto [status, body] = d.request("POST", "/api/jobs", job_body(d, tiles));
    INFO(body.dump());
    REQUIRE(status == 201);
    return body.at("id").get<std::int64_t>();
}

// Submits a job and waits until the line is well into it (8 tiles printed).
std::int64_t submit_until_printing(const test::DaemonProcess& d, int tiles) {
    const auto id = submit(d, tiles);
    REQUIRE(test::eventually([&] { return d.job(id)["printed"].get<int>() >= 8; }, 10s));
    return id;
}

json wait_done(const test::DaemonProcess& d, std::int64_t id, std::chrono::seconds timeout) {
    json job;
    test::eventually(
        [&] {
            job = d.job(id);
            return job.value("status", "") == "done";
        },
        timeout);
    INFO(d.log());
    REQUIRE(job.value("status", "") == "done");
    return job;
}

void check_print_log(const test::LinesimProcess& line, std::int64_t id, int tiles,
                     std::int64_t spoiled) {
    const auto result =
        test::check_print_log(line.print_log(), id, reference_hashes(tiles), spoiled);
    for (const std::string& problem : result.problems)
        FAIL_CHECK(problem);
    CHECK(result.indices_printed == tiles);
}

test::LinesimOptions line_options() {
    test::LinesimOptions o;
    o.speed_mm_s = 1000;
    return o;
}

// 100 tiles a second, and heads that only count the bytes: with 600 x 600 mm tiles at 200 dpi
// (4724 px square, 89 MB) on one render thread, rendering is what falls behind.
test::LinesimOptions render_bound_line_options() {
    test::LinesimOptions o = line_options();
    o.speed_mm_s = 2000;
    o.tile_pitch_mm = 20;
    o.tile_length_mm = 10;
    o.heads_mm = 170;
    o.head_checksums = false;
    return o;
}

test::DaemonOptions render_bound_daemon_options(int queue_tiles) {
    test::DaemonOptions d;
    d.speed_mm_s = 2000;
    d.render_threads = 1;
    d.queue_tiles = queue_tiles;
    return d;
}

std::int64_t submit_large_tiles(const test::DaemonProcess& d, int seed, int tiles) {
    const auto [status, body] =
        d.request("POST", "/api/jobs",
                  R"({"map":")" + d.add_design(TILEJET_TEST_MAP_200DPI) + R"(","seed":)" +
                      std::to_string(seed) + R"(,"tiles":)" + std::to_string(tiles) +
                      R"(,"tile_mm":"600x600","dpi":200})");
    INFO(body.dump());
    REQUIRE(status == 201);
    return body.at("id").get<std::int64_t>();
}

}  // namespace

TEST_CASE("a job prints every tile exactly once with the offline render's bytes",
          "[daemon][line]") {
    test::LinesimProcess line(line_options());
    test::TempDir dir;
    test::DaemonProcess daemon(line, dir.path());

    // A job whose map is missing or corrupt is refused at submit, naming the field.
    auto [status, body] = daemon.request(
        "POST", "/api/jobs", R"({"map":"x.tjmap","seed":1,"tiles":3,"tile_mm":"200x200"})");
    CHECK(status == 400);
    CHECK(body["field"] == "map");
    const auto corrupt = dir.path() / "corrupt.tjmap";
    std::ofstream(corrupt) << "TJMAP\r\n\x1a not a map";
    std::tie(status, body) = daemon.request("POST", "/api/jobs",
                                            R"({"map":")" + daemon.add_design(corrupt) +
                                                R"(","seed":1,"tiles":3,"tile_mm":"200x200"})");
    CHECK(status == 400);
    CHECK(body["field"] == "map");
    std::tie(status, body) = daemon.request(
        "POST", "/api/jobs",
        R"({"map":")" + daemon.add_design(TILEJET_TEST_MAP) +
            R"(","seed":1,"tiles":3,"tile_mm":"200x200","profile":"nonexistent.icc"})");
    CHECK(status == 400);
    CHECK(body["field"] == "profile");

    // ...and the queue keeps working.
    const int tiles = 25;
    const auto id = submit(daemon, tiles);
    const json job = wait_done(daemon, id, 30s);
    CHECK(job["printed"] == tiles);
    check_print_log(line, id, tiles, 0);
    CHECK(std::filesystem::exists(dir.path() / "previews" / ("job-" + std::to_string(id)) /
                                  "tile-0.png"));
}

TEST_CASE("killed with SIGKILL at random moments, the daemon resumes and prints each tile once",
          "[daemon][line][crash]") {
    test::LinesimProcess line(line_options());
    test::TempDir dir;
    test::DaemonProcess daemon(line, dir.path());
    const int tiles = 40;
    const auto id = submit(daemon, tiles);
    std::mt19937 random(std::random_device{}());
    std::uniform_int_distribution<int> ms(300, 1500);
    for (int run = 0; run < 4; ++run) {
        std::this_thread::sleep_for(std::chrono::milliseconds(ms(random)));
        daemon.stop(SIGKILL);
        std::this_thread::sleep_for(std::chrono::milliseconds(ms(random) / 3));
        daemon.start();
    }
    const json job = wait_done(daemon, id, 40s);
    INFO(daemon.log());
    check_print_log(line, id, tiles, 0);
    // Each restart found out what the heads held before sending anything.
    CHECK(daemon.log().find("resync: heads hold") != std::string::npos);
}

TEST_CASE(
    "an e-stop mid-run spoils the tile under the heads, and after acknowledge the job completes",
    "[daemon][line][estop]") {
    test::LinesimProcess line(line_options());
    test::TempDir dir;
    test::DaemonProcess daemon(line, dir.path());
    const int tiles = 30;
    const auto id = submit_until_printing(daemon, tiles);
    line.control("estop on");
    REQUIRE(test::eventually(
        [&] { return daemon.request("GET", "/api/status").second["state"] == "e-stop"; }, 2s));
    CHECK(line.status()["print_enable"] == false);
    // Nothing moves while the e-stop is latched, even released, until acknowledged.
    const auto counter = line.status()["tile_counter"];
    line.control("estop off");
    std::this_thread::sleep_for(500ms);
    CHECK(line.status()["tile_counter"] == counter);
    CHECK(line.status()["running"] == false);
    daemon.request("POST", "/api/line/acknowledge", "");
    const json job = wait_done(daemon, id, 30s);
    check_print_log(line, id, tiles, job["spoiled"].get<std::int64_t>());
}

TEST_CASE("a Modbus link drop mid-run ends with every tile printed exactly once",
          "[daemon][line][link]") {
    test::LinesimProcess line(line_options());
    test::TempDir dir;
    test::DaemonProcess daemon(line, dir.path());
    const int tiles = 30;
    const auto id = submit_until_printing(daemon, tiles);
    line.control("drop-link 1.0");
    REQUIRE(test::eventually(
        [&] { return daemon.request("GET", "/api/status").second["link_up"] == false; }, 3s));
    wait_done(daemon, id, 30s);
    check_print_log(line, id, tiles, 0);
    CHECK(daemon.log().find("PLC link down") != std::string::npos);
}

TEST_CASE("when rendering cannot keep up the conveyor is slowed and the state says why",
          "[daemon][line][render]") {
    test::LinesimProcess line(render_bound_line_options());
    test::TempDir dir;
    test::DaemonProcess daemon(line, dir.path(), render_bound_daemon_options(2));
    submit_large_tiles(daemon, 5, 12);
    // Both are watched while they happen: once rendering catches up the daemon may step the
    // speed back up, so a single look afterwards can miss the slow-down (seen under load).
    bool reason_seen = false, slowed = false;
    REQUIRE(test::eventually(
        [&] {
            const std::string reason =
                daemon.request("GET", "/api/status").second.value("reason", "");
            reason_seen |= reason.find("render behind") != std::string::npos;
            slowed |= line.status()["speed_setpoint"].get<int>() < 2000;
            return reason_seen && slowed;
        },
        20s));
    CHECK(daemon.log().find("conveyor slowed") != std::string::npos);
    // Its tiles are 4724 px square; the previews of the first ones are proofs to look at.
    const auto preview = dir.path() / "previews" / "job-1" / "tile-0.png";
    REQUIRE(test::eventually([&] { return std::filesystem::exists(preview); }, 10s));
    const cv::Mat png = cv::imread(preview.string());
    CHECK(png.cols == 2048);
    CHECK(png.rows == 2048);
}

TEST_CASE("a job whose last tiles are still rendering when the line stops for them finishes",
          "[daemon][line][render]") {
    // Found by the soak: the conveyor, stopped because rendering fell behind, waited for half
    // the queue to be ready, more tiles than were left in the job.
    test::LinesimProcess line(render_bound_line_options());
    test::TempDir dir;
    test::DaemonProcess daemon(line, dir.path(), render_bound_daemon_options(6));
    // The conveyor starts with 2 tiles in the heads and 6 rendered behind them; at 100 tiles/s
    // the last 4 of 12 cannot be ready in time.
    const int tiles = 12;
    const auto id = submit_large_tiles(daemon, 6, tiles);
    const bool done = test::eventually([&] { return daemon.job(id)["status"] == "done"; }, 40s);
    INFO(daemon.log());
    REQUIRE(done);
    CHECK(daemon.log().find("render behind") != std::string::npos);
    CHECK(daemon.job(id)["printed"].get<int>() == tiles);
}

TEST_CASE("SIGHUP reloads the print speed, a broken config is refused and the old one kept",
          "[daemon][line][reload]") {
    test::LinesimProcess line(line_options());
    test::TempDir dir;
    test::DaemonProcess daemon(line, dir.path());
    const std::string original = [&] {
        std::ifstream in(daemon.config_path());
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
    }();
    // [sim] has a speed_mm_s too: change the one in [print].
    const auto print_at = original.find("[print]");
    REQUIRE(print_at != std::string::npos);
    const auto rewrite = [&](const std::string& from, const std::string& to) {
        std::string text = original;
        const auto at = text.find(from, print_at);
        REQUIRE(at != std::string::npos);
        text.replace(at, from.size(), to);
        std::ofstream(daemon.config_path()) << text;
    };

    const int tiles = 60;
    const auto id = submit(daemon, tiles);
    REQUIRE(test::eventually(
        [&] {
            return daemon.job(id)["printed"].get<int>() >= 3 &&
                   line.status()["speed_setpoint"] == 1000;
        },
        10s));
    rewrite("speed_mm_s = 1000", "speed_mm_s = 600");
    daemon.signal(SIGHUP);
    // The running conveyor slows at once.
    CHECK(test::eventually([&] { return line.status()["speed_setpoint"] == 600; }, 3s));
    CHECK(daemon.log().find("reloaded [print]: speed 600 mm/s") != std::string::npos);

    // A config with a mistake is refused as a whole, naming the key, and printing goes on.
    rewrite("speed_mm_s = 1000", "speed_mm_s = 600\nsped_mm_s = 900");
    daemon.signal(SIGHUP);
    CHECK(test::eventually(
        [&] {
            const std::string log = daemon.log();
            return log.find("config not reloaded") != std::string::npos &&
                   log.find("sped_mm_s") != std::string::npos;
        },
        3s));
    wait_done(daemon, id, 60s);
    CHECK(line.status()["speed_setpoint"] == 600);
    check_print_log(line, id, tiles, 0);
}

TEST_CASE("tiles the heads lose before printing are marked missed and printed again",
          "[daemon][line][heads]") {
    test::LinesimProcess line(line_options());
    test::TempDir dir;
    test::DaemonProcess daemon(line, dir.path());
    const int tiles = 30;
    const auto id = submit_until_printing(daemon, tiles);
    // Paused, the conveyor stands with tiles in the heads; then the head controller restarts.
    daemon.request("POST", "/api/line/pause", "");
    REQUIRE(test::eventually(
        [&] {
            const json s = line.status();
            return s["running"] == false && s["head_buffer"].get<int>() > 0;
        },
        5s));
    const int held = line.status()["head_buffer"].get<int>();
    line.control("heads-reset");
    daemon.request("POST", "/api/line/resume", "");
    const json job = wait_done(daemon, id, 30s);
    CHECK(job["missed"] == held);
    CHECK(daemon.log().find("heads lost") != std::string::npos);
    check_print_log(line, id, tiles, 0);
}

// A counter stuck for fewer tiles than the photo-eye check can tell leaves tiles printed but
// uncounted in the head mirror. The next start asks the heads what they hold: they hold fewer
// than the mirror, and those tiles were printed, not lost (a 30-minute soak printed one twice).
TEST_CASE("tiles printed while the counter stuck for a moment are not printed again",
          "[daemon][line][heads][counter]") {
    const int stuck_for = GENERATE(1, 2);
    // Paused and resumed, the heads are asked what they hold before the conveyor starts again;
    // left running, they are asked when the job's last tiles seem never to arrive.
    const bool pause = GENERATE(true, false);
    test::LinesimProcess line(line_options());
    test::TempDir dir;
    test::DaemonProcess daemon(line, dir.path());
    const int tiles = 30;
    const auto id = submit_until_printing(daemon, tiles);
    const auto printed_before = line.status()["printed"].get<int>();
    line.control("counter-stuck on");
    REQUIRE(test::eventually(
        [&] { return line.status()["printed"].get<int>() >= printed_before + stuck_for; }, 5s));
    line.control("counter-stuck off");
    if (pause) {
        daemon.request("POST", "/api/line/pause", "");
        REQUIRE(test::eventually([&] { return line.status()["running"] == false; }, 5s));
        daemon.request("POST", "/api/line/resume", "");
    }
    const json job = wait_done(daemon, id, 30s);
    INFO(daemon.log());
    CHECK(job["missed"] == 0);
    check_print_log(line, id, tiles, 0);
}

TEST_CASE("SIGTERM stops the daemon even when the PLC cannot be reached", "[daemon][line][term]") {
    auto line = std::make_unique<test::LinesimProcess>(line_options());
    test::TempDir dir;
    test::DaemonProcess daemon(*line, dir.path());
    REQUIRE(test::eventually(
        [&] { return daemon.request("GET", "/api/status").second["link_up"] == true; }, 5s));
    line.reset();  // the line simulator (PLC, GPIO chip, heads) is gone
    INFO(daemon.log());
    REQUIRE(test::eventually(
        [&] { return daemon.request("GET", "/api/status").second["state"] == "faulted"; }, 5s));
    const auto t0 = std::chrono::steady_clock::now();
    daemon.stop(SIGTERM);  // SIGKILL after 10 s
    CHECK(std::chrono::steady_clock::now() - t0 < 5s);
    CHECK(daemon.log().find("stopped") != std::string::npos);
}

// A PLC that restarts counts tiles from 0 again; one that lies jumps ahead, or reads a speed
// the line was never asked for. Before, the daemon took a counter going back as 4 billion
// arrivals and walked them one by one: the status froze, the conveyor kept running, stop and
// SIGTERM went unheard.
TEST_CASE(
    "a tile counter that goes back or jumps ahead, or a speed reading out of range, stops the "
    "line until acknowledged, and the job still prints every tile once",
    "[daemon][line][counter]") {
    const std::string glitch = GENERATE(std::string("back"), std::string("ahead"),
                                        std::string("speed"), std::string("stuck"));
    test::LinesimProcess line(line_options());
    test::TempDir dir;
    test::DaemonProcess daemon(line, dir.path());
    const int tiles = 30;
    const auto id = submit_until_printing(daemon, tiles);
    const auto counter = line.status()["tile_counter"].get<std::uint32_t>();
    if (glitch == "speed")
        line.control("speed-reading 60000");  // the line runs at 1000 mm/s (line_options)
    else if (glitch == "stuck")
        line.control("counter-stuck on");  // tiles pass the eye and the heads uncounted
    else
        line.control("counter " + std::to_string(glitch == "back" ? 0u : counter + 1000u));
    json status;
    // A stuck counter shows once more tiles passed the eye than can be on their way.
    REQUIRE(test::eventually(
        [&] {
            status = daemon.request("GET", "/api/status").second;
            return status["counter_fault"] == true;
        },
        glitch == "stuck" ? 10s : 3s));
    INFO(status.dump());
    CHECK(status["state"] == "faulted");
    const char* why = glitch == "back"    ? "went back"
                      : glitch == "ahead" ? "jumped"
                      : glitch == "speed" ? "speed"
                                          : "stuck";
    CHECK(status["reason"].get<std::string>().find(why) != std::string::npos);
    // Stopped and held: nothing moves or prints until the operator acknowledges.
    REQUIRE(test::eventually([&] { return line.status()["running"] == false; }, 2s));
    CHECK(line.status()["print_enable"] == false);
    const auto printed = daemon.job(id)["printed"];
    std::this_thread::sleep_for(500ms);
    CHECK(line.status()["running"] == false);
    CHECK(daemon.job(id)["printed"] == printed);
    CHECK(status["faults"].dump().find("plc_counter") != std::string::npos);
    if (glitch == "speed") line.control("speed-reading off");  // the sensor is mended
    if (glitch == "stuck") line.control("counter-stuck off");
    daemon.request("POST", "/api/line/acknowledge", "");
    wait_done(daemon, id, 30s);
    check_print_log(line, id, tiles, 0);
    CHECK(daemon.log().find("PLC reading fault acknowledged") != std::string::npos);
}

TEST_CASE("SIGTERM ends the daemon while a counter fault holds the line", "[daemon][line][term]") {
    test::LinesimProcess line(line_options());
    test::TempDir dir;
    test::DaemonProcess daemon(line, dir.path());
    submit_until_printing(daemon, 30);
    line.control("counter 0");
    REQUIRE(test::eventually(
        [&] { return daemon.request("GET", "/api/status").second["counter_fault"] == true; }, 3s));
    const auto t0 = std::chrono::steady_clock::now();
    daemon.stop(SIGTERM);
    CHECK(std::chrono::steady_clock::now() - t0 < 5s);
    CHECK(line.status()["running"] == false);
}

TEST_CASE("a job pins its design: a design file replaced before the job resumes is refused",
          "[daemon][line][pin]") {
    test::LinesimProcess line(line_options());
    test::TempDir dir;
    test::DaemonProcess daemon(line, dir.path());
    const auto design = daemon.designs() / daemon.add_design(TILEJET_TEST_MAP, "design.tjmap");
    const auto [status, body] =
        daemon.request("POST", "/api/jobs",
                       R"({"map":"design.tjmap",)"
                       R"("seed":4242,"tiles":200,"tile_mm":"200x200","dpi":20})");
    REQUIRE(status == 201);
    const auto id = body.at("id").get<std::int64_t>();
    const std::string submitted_id = body.at("map_id").get<std::string>();
    CHECK(submitted_id.size() == 64);
    REQUIRE(test::eventually([&] { return daemon.job(id)["printed"].get<int>() >= 4; }, 10s));
    daemon.stop(SIGKILL);
    // Another design under the same name: the tiles it would print under the job's indices
    // are not the ones the job began with.
    std::filesystem::copy_file(TILEJET_SOURCE_DIR "/tests/synth/data/legacy-one-cell-image.tjmap",
                               design, std::filesystem::copy_options::overwrite_existing);
    daemon.start();
    json job;
    REQUIRE(test::eventually(
        [&] {
            job = daemon.job(id);
            return job.value("status", "") == "failed";
        },
        10s));
    const std::string message = job.value("message", "");
    INFO(message);
    CHECK(message.find("job-" + std::to_string(id)) != std::string::npos);
    CHECK(message.find(design.string()) != std::string::npos);
    CHECK(message.find(submitted_id) != std::string::npos);
    CHECK(message.find("is now map ") != std::string::npos);
    // The panel's pictures come from the same job setup: no preview of the other design's tiles.
    const auto [preview_status, preview] =
        daemon.request("GET", "/api/jobs/" + std::to_string(id) + "/tiles/0.png");
    CHECK(preview_status == 409);
    CHECK(preview.value("error", "").find("is now map ") != std::string::npos);
}

TEST_CASE("previews left by another job of the same number are replaced, not shown as this job's",
          "[daemon][line][previews]") {
    // A new job store numbers jobs from 1 again (the demo makes one every run): the proofs of
    // the last store's job 1, of another design, were kept and shown as the new job 1's.
    test::LinesimProcess line(line_options());
    test::TempDir dir;
    const auto old_job = dir.path() / "previews" / "job-1";
    std::filesystem::create_directories(old_job);
    std::ofstream(old_job / "tile-0.png") << "a proof of another job";
    test::DaemonProcess daemon(line, dir.path());
    const auto id = submit(daemon, 4);
    REQUIRE(id == 1);
    wait_done(daemon, id, 30s);
    std::ifstream proof(old_job / "tile-0.png", std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(proof)), {});
    CHECK(bytes.substr(1, 3) == "PNG");
    CHECK(std::filesystem::exists(old_job / "job.txt"));
}
