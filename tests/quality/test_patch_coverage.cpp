#include <catch2/catch.hpp>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "../synth/fixtures.hpp"
#include "tilejet/quality/patch_coverage.hpp"
#include "tilejet/quality/patch_labels.hpp"
#include "tilejet/synth/error.hpp"
#include "tilejet/synth/map_file.hpp"

using namespace tilejet;

TEST_CASE("patch coverage is the share of pixels patch labels mark", "[quality]") {
    const synth::TextureMap& map = test::small_map();
    // Regions straddling the origin, far out, and one narrower than a cell: clipping of runs at
    // every edge must count exactly what the labels show.
    for (const synth::Region region :
         {synth::Region{-70, 33, 300, 200}, synth::Region{(int64_t(1) << 31) - 300, -5, 300, 90},
          synth::Region{5, -3, 17, 230}}) {
        for (uint64_t seed : {1u, 9u}) {
            const cv::Mat labels = quality::render_patch_labels(map, seed, region);
            const double want =
                double(cv::countNonZero(labels)) / double(region.width * region.height);
            CHECK(quality::patch_coverage(map, seed, region) == want);
        }
    }
    // The demo map's patches cover some of the plane but not all of it.
    const double share = quality::patch_coverage(map, 1, {0, 0, 512, 512});
    CHECK(share > 0.0);
    CHECK(share < 1.0);
}

TEST_CASE("patch coverage refuses an empty region", "[quality]") {
    const synth::TextureMap& map = test::small_map();
    CHECK_THROWS_AS(quality::patch_coverage(map, 1, {0, 0, 0, 10}), synth::SynthError);
    CHECK_THROWS_AS(quality::patch_coverage(map, 1, {0, 0, -4, 10}), synth::SynthError);
}

TEST_CASE("map info states patch coverage of its fixed region", "[quality]") {
    const test::TempDir dir;
    synth::save_texture_map(test::small_map(), dir / "small.tjmap");
    const std::string command = std::string(TILEJET_CLI) + " map info " +
                                (dir / "small.tjmap").string() + " > " + (dir / "info").string();
    REQUIRE(std::system(command.c_str()) == 0);
    std::ifstream in(dir / "info");
    const nlohmann::json info = nlohmann::json::parse(in);
    // 2048 x 2048 px at the origin, job seed 1: the region the README names.
    CHECK(info["patch_coverage"].get<double>() ==
          quality::patch_coverage(test::small_map(), 1, {0, 0, 2048, 2048}));
}
