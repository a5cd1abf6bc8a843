// The API as tilejetd serves it on the simulated line: pictures from the job's own tiles,
// faults in plain words, live events, an engineer's upload, and a shutdown with panels open.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <thread>

#include "daemon_process.hpp"
#include "tilejet/colour/cmyk_map.hpp"
#include "tilejet/synth/map_file.hpp"
#include "tilejet/synth/sampler.hpp"
#include "tilejet/synth/tile_region.hpp"

using namespace tilejet;
using namespace std::chrono_literals;
using nlohmann::json;

namespace {

constexpr int kSide = 157;  // 200 mm at 20 dpi

test::LinesimOptions line_options() {
    test::LinesimOptions o;
    o.speed_mm_s = 1000;
    return o;
}

std::int64_t submit(const test::DaemonProcess& d, int tiles) {
    const auto [status, body] =
        d.request("POST", "/api/jobs",
                  R"({"map":")" + d.add_design(TILEJET_TEST_MAP) + R"(","seed":99,"tiles":)" +
                      std::to_string(tiles) + R"(,"tile_mm":"200x200","dpi":20})");
    INFO(body.dump());
    REQUIRE(status == 201);
    return body.at("id").get<std::int64_t>();
}

// The tile's soft proof rendered here through synth and colour (not the daemon's code),
// averaged: what the thumbnail's mean colour must come close to.
cv::Scalar reference_mean_rgb(std::int64_t index) {
    const synth::TextureMap map = synth::load_texture_map(TILEJET_TEST_MAP);
    colour::ColourSettings settings;
    settings.output_profile = TILEJET_TEST_CMYK_PROFILE;
    const colour::CmykTransform transform(settings);
    const auto cmyk = colour::convert_map(map, transform);
    const auto region = synth::tile_region(99, std::uint64_t(index), {kSide, kSide});
    return cv::mean(transform.proof(synth::render_region(*cmyk, 99, region, 1)));
}

cv::Mat get_png(const test::DaemonProcess& d, const std::string& path) {
    auto c = d.client();
    const auto r = c.Get(path.c_str(), d.sign_in("vera").headers);
    REQUIRE(r);
    INFO(r->body.substr(0, 200));
    REQUIRE(r->status == 200);
    CHECK(r->get_header_value("Content-Type") == "image/png");
    const std::vector<std::uint8_t> bytes(r->body.begin(), r->body.end());
    return cv::imdecode(bytes, cv::IMREAD_COLOR);
}

}  // namespace

TEST_CASE("the panel's pictures are soft proofs of the job's own tiles",
          "[api][daemon][pictures]") {
    test::LinesimProcess line(line_options());
    test::TempDir dir;
    test::DaemonProcess daemon(line, dir.path());
    const auto id = submit(daemon, 40);
    json status;
    REQUIRE(test::eventually(
        [&] {
            status = daemon.request("GET", "/api/status").second;
            return status.contains("job") && status["job"]["printed"].get<int>() >= 3;
        },
        20s));
    CHECK(status["job"]["id"] == id);
    CHECK(status["job"]["remaining"] == 40 - status["job"]["printed"].get<int>());
    REQUIRE(status["next_tiles"].is_array());
    CHECK_FALSE(status["next_tiles"].empty());
    CHECK(status["next_tiles"][0].get<int>() >= 0);
    CHECK(status["faults"].empty());

    for (const std::int64_t k : {std::int64_t(0), std::int64_t(17)}) {
        INFO("tile " << k);
        const cv::Mat thumb = get_png(daemon, "/api/jobs/" + std::to_string(id) + "/tiles/" +
                                                  std::to_string(k) + ".png?size=64");
        REQUIRE_FALSE(thumb.empty());
        CHECK(std::max(thumb.cols, thumb.rows) == 64);
        const cv::Scalar got = cv::mean(thumb);         // B, G, R
        const cv::Scalar want = reference_mean_rgb(k);  // R, G, B
        for (int c = 0; c < 3; ++c) {
            INFO("channel " << c << ": " << got[2 - c] << " vs " << want[c]);
            CHECK(std::abs(got[2 - c] - want[c]) < 4.0);
        }
    }
    // Tiles of two different indices are different pictures.
    const cv::Mat a = get_png(daemon, "/api/jobs/" + std::to_string(id) + "/tiles/1.png?size=32");
    const cv::Mat b = get_png(daemon, "/api/jobs/" + std::to_string(id) + "/tiles/2.png?size=32");
    CHECK(cv::norm(a, b, cv::NORM_L1) > 0);

    const cv::Mat wall = get_png(daemon, "/api/wall.png?tiles=4&size=200");
    REQUIRE_FALSE(wall.empty());
    CHECK(wall.cols <= 200);
    CHECK(wall.cols > 100);  // four tiles side by side in two columns, not one
    const auto [missing, body] =
        daemon.request("GET", "/api/jobs/" + std::to_string(id) + "/tiles/40.png");
    CHECK(missing == 404);
    CHECK(body["field"] == "tile");
    CHECK(daemon.request("POST", "/api/line/stop").first == 200);
}

TEST_CASE("an e-stop shows as a fault saying what to do, until acknowledged",
          "[api][daemon][faults]") {
    test::LinesimProcess line(line_options());
    test::TempDir dir;
    test::DaemonProcess daemon(line, dir.path());
    line.control("estop on");
    json faults;
    REQUIRE(test::eventually(
        [&] {
            faults = daemon.request("GET", "/api/status").second["faults"];
            return !faults.empty() && faults[0]["code"] == "estop";
        },
        5s));
    CHECK(faults[0]["severity"] == "stop");
    CHECK_THAT(faults[0]["action"].get<std::string>(), Catch::Contains("Acknowledge"));
    line.control("estop off");
    daemon.request("POST", "/api/line/acknowledge");
    CHECK(test::eventually(
        [&] { return daemon.request("GET", "/api/status").second["faults"].empty(); }, 5s));
}

TEST_CASE("the daemon's event stream follows a job, and SIGTERM ends it promptly",
          "[api][daemon][events]") {
    test::LinesimProcess line(line_options());
    test::TempDir dir;
    test::DaemonProcess daemon(line, dir.path());
    std::mutex mutex;
    std::string text;
    std::atomic<bool> ended{false};
    std::thread reader([&] {
        auto c = daemon.client();
        c.set_read_timeout(60, 0);
        c.Get("/api/events", daemon.sign_in("vera").headers, [&](const char* data, size_t n) {
            std::lock_guard lock(mutex);
            text.append(data, n);
            return true;
        });
        ended = true;
    });
    submit(daemon, 12);
    // Progress arrives as events: several different printed counts of the job go by.
    const auto printed_counts = [&] {
        std::lock_guard lock(mutex);
        std::set<int> seen;
        for (size_t at = text.find("\"printed\":"); at != std::string::npos;
             at = text.find("\"printed\":", at + 1))
            seen.insert(std::atoi(text.c_str() + at + 10));
        return seen.size();
    };
    CHECK(test::eventually([&] { return printed_counts() >= 3; }, 20s));
    const auto start = std::chrono::steady_clock::now();
    daemon.stop(SIGTERM);
    const auto took = std::chrono::steady_clock::now() - start;
    INFO(daemon.log());
    CHECK(took < 8s);  // stop() would SIGKILL at 10 s
    CHECK(daemon.log().find("tilejetd: stopped") != std::string::npos);
    CHECK(test::eventually([&] { return ended.load(); }, 5s));
    reader.join();
}

TEST_CASE("an engineer adds a design, an operator may not", "[api][daemon][designs]") {
    test::LinesimProcess line(line_options());
    test::TempDir dir;
    test::DaemonProcess daemon(line, dir.path());
    std::ifstream in(TILEJET_TEST_MAP, std::ios::binary);
    const std::string map((std::istreambuf_iterator<char>(in)), {});
    const auto engineer = daemon.sign_in("erik");
    CHECK(daemon.request("PUT", "/api/designs/marble.tjmap", map).first == 403);
    auto [status, body] = daemon.request_as(engineer, "PUT", "/api/designs/broken.tjmap",
                                            map.substr(0, map.size() / 2));
    CHECK(status == 400);
    CHECK(body["field"] == "body");
    std::tie(status, body) = daemon.request_as(engineer, "PUT", "/api/designs/marble.tjmap", map);
    INFO(body.dump());
    CHECK(status == 201);
    // Never replaced: queued jobs name the file.
    CHECK(daemon.request_as(engineer, "PUT", "/api/designs/marble.tjmap", map).first == 409);
    const json designs = daemon.request("GET", "/api/designs").second;
    REQUIRE(designs.size() == 1);
    CHECK(designs[0]["name"] == "marble.tjmap");
    CHECK(designs[0]["bytes"] == map.size());
    CHECK(designs[0]["dpi"] == 20);  // what the panel's job form shows and takes
    // A job of the uploaded design is accepted.
    std::tie(status, body) =
        daemon.request("POST", "/api/jobs",
                       R"({"map":")" + designs[0]["name"].get<std::string>() +
                           R"(","seed":1,"tiles":1,"tile_mm":"200x200","dpi":20})");
    CHECK(status == 201);
}

TEST_CASE("a job prints its design at the design's dpi: another is refused, none takes it",
          "[api][daemon][jobs][dpi]") {
    test::LinesimProcess line(line_options());
    test::TempDir dir;
    test::DaemonProcess daemon(line, dir.path());
    // small.tjmap is built for 20 dpi (tests/CMakeLists.txt).
    const std::string design = daemon.add_design(TILEJET_TEST_MAP);
    auto [status, body] = daemon.request(
        "POST", "/api/jobs",
        R"({"map":")" + design + R"(","seed":1,"tiles":1,"tile_mm":"200x200","dpi":30})");
    INFO(body.dump());
    CHECK(status == 400);
    CHECK(body["field"] == "dpi");
    const std::string message = body["error"].get<std::string>();
    CHECK_THAT(message, Catch::Contains("30 dpi") && Catch::Contains("built for 20 dpi"));
    // Without a dpi the job takes the design's, whatever the line's default.
    std::tie(status, body) =
        daemon.request("POST", "/api/jobs",
                       R"({"map":")" + design + R"(","seed":1,"tiles":1,"tile_mm":"200x200"})");
    REQUIRE(status == 201);
    CHECK(body["dpi"] == 20);
    // The command line says the same.
    const std::string command = "TILEJET_API=127.0.0.1:" + std::to_string(daemon.port()) +
                                " TILEJET_USER=" + test::kTestUsers[0].name +
                                " TILEJET_PASSWORD=" + test::kTestUsers[0].password + " " +
                                TILEJET_CLI " job submit --map " TILEJET_TEST_MAP +
                                " --seed 1 --tiles 1 --tile-mm 200x200 --dpi 30 2>&1";
    std::string out;
    FILE* pipe = popen(command.c_str(), "r");
    REQUIRE(pipe);
    char buffer[512];
    while (std::fgets(buffer, sizeof buffer, pipe))
        out += buffer;
    CHECK(pclose(pipe) != 0);
    CHECK_THAT(out, Catch::Contains("30 dpi") && Catch::Contains("built for 20 dpi"));
}

TEST_CASE(
    "of two uploads of one new design name exactly one wins and the file holds its bytes, "
    "a symlink planted in the folder is never written through",
    "[api][daemon][designs]") {
    test::LinesimProcess line(line_options());
    test::TempDir dir;
    test::DaemonProcess daemon(line, dir.path());
    std::ifstream in(TILEJET_TEST_MAP, std::ios::binary);
    const std::string small((std::istreambuf_iterator<char>(in)), {});
    std::ifstream in2(TILEJET_SOURCE_DIR "/tests/synth/data/legacy-one-cell-image.tjmap",
                      std::ios::binary);
    const std::string legacy((std::istreambuf_iterator<char>(in2)), {});
    const auto engineer = daemon.sign_in("erik");
    const auto designs = dir.path() / "designs";
    for (int round = 0; round < 6; ++round) {
        const std::string name = "race-" + std::to_string(round) + ".tjmap";
        int status[2] = {0, 0};
        std::thread a([&] {
            status[0] = daemon.request_as(engineer, "PUT", "/api/designs/" + name, small).first;
        });
        std::thread b([&] {
            status[1] = daemon.request_as(engineer, "PUT", "/api/designs/" + name, legacy).first;
        });
        a.join(), b.join();
        INFO("round " << round << ": " << status[0] << ", " << status[1]);
        REQUIRE(std::count(status, status + 2, 201) == 1);
        REQUIRE(std::count(status, status + 2, 409) == 1);
        std::ifstream file(designs / name, std::ios::binary);
        const std::string held((std::istreambuf_iterator<char>(file)), {});
        CHECK(held == (status[0] == 201 ? small : legacy));
    }
    // No temp file is left behind.
    for (const auto& entry : std::filesystem::directory_iterator(designs))
        CHECK(entry.path().filename().string().front() != '.');

    // A symlink at the old fixed temp name and at the target name: neither is followed.
    const auto victim = dir.path() / "victim.txt";
    std::ofstream(victim) << "keep me";
    std::filesystem::create_symlink(victim, designs / ".planted.tjmap.upload");
    CHECK(daemon.request_as(engineer, "PUT", "/api/designs/planted.tjmap", small).first == 201);
    std::filesystem::create_symlink(victim, designs / "linked.tjmap");
    CHECK(daemon.request_as(engineer, "PUT", "/api/designs/linked.tjmap", small).first == 409);
    std::ifstream v(victim);
    CHECK(std::string((std::istreambuf_iterator<char>(v)), {}) == "keep me");
}
