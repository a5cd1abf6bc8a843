#include <catch2/catch.hpp>
#include <filesystem>
#include <opencv2/core.hpp>

#include "../synth/fixtures.hpp"
#include "tilejet/quality/cell_place_repeat.hpp"
#include "tilejet/quality/patch_labels.hpp"
#include "tilejet/synth/build.hpp"
#include "tilejet/synth/map_file.hpp"

using namespace tilejet;

TEST_CASE("one cell image repeats at every place no patch covers, a set's insides do not",
          "[quality][cell_set]") {
    // The demo design's one-image map as tilejet made it before cell sets (32 px cells).
    const synth::TextureMap one = synth::load_texture_map(
        std::filesystem::path(TILEJET_SOURCE_DIR) / "tests/synth/data/legacy-one-cell-image.tjmap");
    const quality::CellPlaceRepeat r = quality::cell_place_repeat(one, 7);
    const int cw = one.cell_width, ch = one.cell_height;
    REQUIRE(r.cells == 16 * 16);
    REQUIRE(r.band == 3);
    // Every cell without a patch at a place shows the one image's pixel there: at least that
    // share of cells agree. Counted from the patch labels of the same region.
    const cv::Mat labels = quality::render_patch_labels(one, 7, {0, 0, 16 * cw, 16 * ch});
    double uncovered = 0;
    int places = 0;
    for (int v = r.band; v < ch - r.band; ++v)
        for (int u = r.band; u < cw - r.band; ++u, ++places) {
            int bare = 0;
            for (int j = 0; j < 16; ++j)
                for (int i = 0; i < 16; ++i)
                    bare += labels.at<int32_t>(j * ch + v, i * cw + u) == 0;
            uncovered += bare / 256.0;
        }
    uncovered /= places;
    INFO("one image: inside " << r.inside << ", uncovered " << uncovered);
    CHECK(uncovered > 0.3);
    CHECK(r.inside >= uncovered - 1e-9);

    // A set of the same design and cell size: its insides vary (32 images); its borders show
    // the strips, each along one edge in four.
    synth::BuildParams p;
    p.cell_size = 32;
    p.corner_colours = 2;  // as measured; cells this small get 3 by default (session 39)
    p.patches = 12;
    p.candidates = 96;
    p.seed = 3;
    const synth::TextureMap set = synth::build_texture_map(test::demo_exemplar(), p);
    const quality::CellPlaceRepeat s = quality::cell_place_repeat(set, 7);
    INFO("set: border " << s.border << ", inside " << s.inside);
    CHECK(s.inside < 0.25);
    CHECK(s.inside < r.inside / 2);
    CHECK(s.border > s.inside);
    CHECK(s.border <= 1.0);
}
