#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
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
          "tilejet-seams.png", "canvas-wall.png", "cell-repeats.png", "quilt-seams.png",
          "wall3x3-tilejet.png", "wall3x3-canvas.png", "wall3x3-quilt.png",
          "walls-side-by-side.png", "cell-lines.png"})
        CHECK(std::filesystem::exists(report / file));

    std::ifstream in(report / "metrics.json");
    const nlohmann::ordered_json m = nlohmann::ordered_json::parse(in);
    REQUIRE(m.size() == 5);
    // The gates come first, as on the page: a reader of the file sees the verdict before the
    // figures that explain it.
    REQUIRE(m.begin().key() == "gates");
    const auto& gates = m["gates"];
    CHECK(gates["limit"] == 1.2);
    CHECK(gates["periodicity"] == m["tilejet"]["periodicity"]);
    CHECK(gates["texture_energy_vs_quilt"].get<double>() ==
          Approx(m["tilejet"]["texture_energy"].get<double>() /
                 m["quilt"]["texture_energy"].get<double>()));
    CHECK(gates["grid_lines_limit"] == 1.15);
    CHECK(gates["grid_lines"].get<double>() == std::max(gates["grid_lines_rows"].get<double>(),
                                                        gates["grid_lines_columns"].get<double>()));
    CHECK(gates["grid_lines_pass"] == (gates["grid_lines"].get<double>() <= 1.15));
    CHECK(gates["pass"] == (gates["periodicity"].get<double>() <= 1.2 &&
                            gates["texture_energy_vs_quilt"].get<double>() <= 1.2 &&
                            gates["grid_lines"].get<double>() <= 1.15));
    const double coverage = m["tilejet"]["patch_coverage"];
    CHECK(gates["patch_coverage"] == coverage);
    CHECK(coverage > 0);
    CHECK(coverage < 1);
    // The grid a fold by the cell size shows: in the gates as in tilejet's figures.
    const auto& fold = m["tilejet"]["cell_place_repeat"];
    CHECK(gates["cell_border_repeat"] == fold["border"]);
    CHECK(gates["cell_inside_repeat"] == fold["inside"]);
    CHECK(fold["inside"].get<double>() > 0);
    CHECK(fold["border"].get<double>() <= 1);
    // Where the coherence goes: in the gates as in tilejet's figures, next to quilt's.
    const auto& place = m["tilejet"]["cell_place_energy"];
    CHECK(gates["coherence_border"] == place["border"]);
    CHECK(gates["coherence_inside"] == place["inside"]);
    CHECK(gates["quilt_coherence"] == m["quilt"]["texture_coherence"]);
    CHECK(place["border"].get<double>() > 0);
    CHECK(place["inside"].get<double>() >= 0);
    // Lines along the cell grid: in the gates as in tilejet's figures, where in the cell.
    const auto& lines = m["tilejet"]["cell_grid_lines"];
    CHECK(gates["grid_lines_rows"] == lines["rows"]);
    CHECK(gates["grid_lines_columns"] == lines["columns"]);
    CHECK(lines["rows"].get<double>() > 0);
    CHECK(lines["row_at"].get<int>() >= 0);
    CHECK(lines["column_at"].get<int>() < 64);
    // The correlation at whole cells: in the gates as in tilejet's figures, over some lags.
    const auto& lag = m["tilejet"]["cell_lag_correlation"];
    CHECK(gates["whole_cell_correlation"] == lag["whole_cells"]);
    CHECK(gates["half_cell_correlation"] == lag["half_cells"]);
    CHECK(lag["lags"].get<int>() > 0);
    CHECK(std::abs(lag["whole_cells"].get<double>()) <= 1);
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
        for (const char* tail : {"light_tail_share", "dark_tail_share"}) {
            const double share = j["colour"][tail];
            CHECK(share >= 0);
            CHECK(share <= 1);
        }
    }
    // The cell baseline is one 64 px cell image over and over: every window of it recurs, and
    // the only seams it has are unknown.
    CHECK(m["cell"]["repeat_curve"]["16"] == 1.0);
    CHECK(m["cell"]["repeat_curve"]["64"] == 1.0);
    CHECK(m["cell"]["seam"].is_null());
    CHECK(m["cell"]["periodicity"].get<double>() > 2);
    CHECK(m["tilejet"]["seam"]["mean"].get<double>() > 0);

    // The page and the printed summary open with the gates, then the walls side by side.
    std::ifstream page_in(report / "index.html");
    const std::string page((std::istreambuf_iterator<char>(page_in)),
                           std::istreambuf_iterator<char>());
    const size_t gates_at = page.find("Gates: "), walls_at = page.find("walls-side-by-side.png");
    REQUIRE(gates_at != std::string::npos);
    REQUIRE(walls_at != std::string::npos);
    CHECK(gates_at < walls_at);
    CHECK(walls_at < page.find("<img src='exemplar.png'>"));
    // Where the lines gate's tone changes lie in the cell, after the walls.
    CHECK(page.find("<img src='cell-lines.png'>") != std::string::npos);
    CHECK(page.find("<img src='cell-lines.png'>") > walls_at);
    CHECK(page.find("<img") > gates_at);
    std::ifstream log_in(dir / "log");
    const std::string log((std::istreambuf_iterator<char>(log_in)),
                          std::istreambuf_iterator<char>());
    CHECK(log.starts_with("gates (limit 1.2"));
    // What the gates were measured against, beside them: small_map()'s source is its exemplar
    // (a quilted enlargement would hide what the quilt lost).
    CHECK(log.find("measured against          the map's source, which is the exemplar itself") <
          log.find("periodicity"));
}
