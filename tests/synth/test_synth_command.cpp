// tilejet synth, analyze --mask and map build --colour-gain through the command line: outputs
// and the errors a user sees.

#include <catch2/catch.hpp>
#include <cstdlib>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "fixtures.hpp"

using namespace tilejet;

namespace {

struct Run {
    int status;
    std::string output;  // stdout and stderr
};

Run run(const test::TempDir& dir, const std::string& args) {
    const auto log = dir / "log";
    const std::string command =
        std::string(TILEJET_CLI) + " " + args + " > " + log.string() + " 2>&1";
    const int status = std::system(command.c_str());
    std::ifstream in(log);
    std::stringstream text;
    text << in.rdbuf();
    return {status, text.str()};
}

std::string write_brick(const test::TempDir& dir) {
    cv::Mat bgr;
    cv::cvtColor(test::make_lattice_texture({{40, 0}, {20, 17}}, {233, 191}, 4), bgr,
                 cv::COLOR_RGB2BGR);
    const std::string path = (dir / "brick.png").string();
    cv::imwrite(path, bgr);
    return path;
}

std::string file_bytes(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

TEST_CASE("synth command: writes the size asked for, the same bytes for the same seed",
          "[synth][cli]") {
    const test::TempDir dir;
    const std::string brick = write_brick(dir);
    for (const char* method : {"quilt", "rsgf", "enm"}) {
        INFO(method);
        const std::string base = "synth " + brick + " --method " + method + " --size 90x70";
        REQUIRE(run(dir, base + " --seed 3 -o " + (dir / "a.png").string()).status == 0);
        REQUIRE(run(dir, base + " --seed 3 -o " + (dir / "b.png").string()).status == 0);
        const cv::Mat a = cv::imread((dir / "a.png").string());
        CHECK(a.cols == 90);
        CHECK(a.rows == 70);
        CHECK(file_bytes(dir / "a.png") == file_bytes(dir / "b.png"));
    }
}

TEST_CASE("synth command: broken input names the option or file", "[synth][cli]") {
    const test::TempDir dir;
    const std::string brick = write_brick(dir), out = " -o " + (dir / "o.png").string();

    Run r = run(dir, "synth " + brick + " --method quilt --size 90by70" + out);
    CHECK(r.status != 0);
    CHECK_THAT(r.output, Catch::Contains("--size") && Catch::Contains("90by70"));
    r = run(dir, "synth " + brick + " --method quilt --size 0x70" + out);
    CHECK(r.status != 0);
    CHECK_THAT(r.output, Catch::Contains("--size"));

    r = run(dir, "synth " + brick + " --method wavelets --size 90x70" + out);
    CHECK(r.status != 0);
    CHECK_THAT(r.output, Catch::Contains("--method") && Catch::Contains("wavelets") &&
                             Catch::Contains("quilt, rsgf or enm"));

    const std::string missing = (dir / "no-such-exemplar.png").string();
    r = run(dir, "synth " + missing + " --method enm --size 90x70" + out);
    CHECK(r.status != 0);
    CHECK_THAT(r.output, Catch::Contains("no-such-exemplar.png"));
    CHECK_FALSE(std::filesystem::exists(dir / "o.png"));
}

TEST_CASE("analyze --mask writes the exemplar-sized grey mask", "[fourier][cli]") {
    const test::TempDir dir;
    const std::string brick = write_brick(dir);
    const Run r = run(dir, "analyze " + brick + " --mask " + (dir / "mask.png").string());
    REQUIRE(r.status == 0);
    CHECK_THAT(r.output, Catch::Contains("\"v1\""));
    const cv::Mat mask = cv::imread((dir / "mask.png").string(), cv::IMREAD_UNCHANGED);
    CHECK(mask.type() == CV_8U);
    CHECK(mask.size() == cv::Size(233, 191));
}

TEST_CASE("map build --colour-gain on a stochastic exemplar is an error naming the option",
          "[colour_gain][cli]") {
    const test::TempDir dir;
    const std::string marble = std::string(TILEJET_SOURCE_DIR) + "/config/demo/green-marble.png";
    const Run r =
        run(dir, "map build " + marble + " --exemplar-dpi 50 --dpi 50 --colour-gain 2 -o " +
                     (dir / "m.tjmap").string());
    CHECK(r.status != 0);
    CHECK_THAT(r.output, Catch::Contains("--colour-gain") && Catch::Contains("stochastic"));
    const Run e =
        run(dir, "map build " + marble + " --exemplar-dpi 50 --dpi 50 --enlarge poisson -o " +
                     (dir / "m.tjmap").string());
    CHECK(e.status != 0);
    CHECK_THAT(e.output, Catch::Contains("--enlarge") && Catch::Contains("poisson"));
}
