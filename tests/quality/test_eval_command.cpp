#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "../synth/fixtures.hpp"
#include "tilejet/synth/map_file.hpp"

using namespace tilejet;

TEST_CASE("tilejet eval writes the report, its pictures and metrics.json", "[quality]") {
    const test::TempDir dir;
    synth::save_texture_map(test::small_map(), dir / "small.tjmap");
    const std::string command =
        std::string(TILEJET_CLI) + " eval " + (dir / "small.tjmap").string() +
        " --seed 3 --tiles 6 --tile-size 96x96 --threads 2 --profile " + TILEJET_TEST_CMYK_PROFILE +
        " -o " + (dir / "report").string() + " > " + (dir / "log").string() + " 2>&1";
    REQUIRE(std::system(command.c_str()) == 0);

    const auto report = dir / "report";
    for (const char* file :
         {"index.html", "exemplar.png", "tilejet-wall.png", "tilejet-repeats.png",
          "tilejet-seams.png", "canvas-wall.png", "cell-repeats.png", "quilt-seams.png"})
        CHECK(std::filesystem::exists(report / file));

    std::ifstream in(report / "metrics.json");
    const nlohmann::json m = nlohmann::json::parse(in);
    REQUIRE(m.size() == 4);
    for (const char* method : {"tilejet", "canvas", "cell", "quilt"}) {
        INFO(method);
        REQUIRE(m.contains(method));
        const auto& j = m[method];
        for (const char* key : {"repeat_curve", "repeat_scale", "tile_pairs_sharing", "periodicity",
                                "texture_energy", "seam", "colour"})
            CHECK(j.contains(key));
        CHECK(j["repeat_curve"].size() == 3);  // 16, 32, 64 fit in 96 px tiles
        const double gamut = j["colour"]["out_of_gamut_share"];
        CHECK(gamut >= 0);
        CHECK(gamut <= 1);
        CHECK(j["colour"]["soft_proof_delta_e2000"].get<double>() > 0);
    }
    // The cell baseline is one 64 px cell image over and over: every window of it recurs, and
    // the only seams it has are unknown.
    CHECK(m["cell"]["repeat_curve"]["16"] == 1.0);
    CHECK(m["cell"]["repeat_curve"]["64"] == 1.0);
    CHECK(m["cell"]["seam"].is_null());
    CHECK(m["cell"]["periodicity"].get<double>() > 2);
    CHECK(m["tilejet"]["seam"]["mean"].get<double>() > 0);
}
