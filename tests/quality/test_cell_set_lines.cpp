// A cell set's plane against the lines along the cell grid (cell_grid_lines.hpp): with its
// frames' depth and its blocks' joints the same in every image, a wall of the corpus's slate
// showed its cells as squares; wandering, image by image, far less.

#include <catch2/catch.hpp>
#include <filesystem>

#include "tilejet/quality/cell_grid_lines.hpp"
#include "tilejet/quality/cell_stretch.hpp"
#include "tilejet/synth/build.hpp"
#include "tilejet/synth/exemplar.hpp"

using namespace tilejet;

TEST_CASE("a set's cells show fewer lines along the grid than straight frames drew",
          "[quality][cell_set][heavy]") {
    const cv::Mat slate = synth::load_exemplar(
        std::filesystem::path(TILEJET_SOURCE_DIR) / "tests/quality/corpus/slate.png", {});
    // Two map seeds: one says little, the figure swings by a tenth or so from seed to seed.
    double straight = 0, wandering = 0;
    for (const uint64_t seed : {1, 2}) {
        synth::BuildParams p;  // defaults, as scripts/corpus-eval builds it: 256 px cells
        p.seed = seed;
        const auto lines_of = [&](bool wander) {
            p.wandering_frames = wander;
            const synth::TextureMap set = synth::build_texture_map(slate, p);
            REQUIRE(set.cell_images.size() == 36);
            return quality::cell_grid_lines(
                quality::cell_stretch_plane(set, 7, quality::kWideStretch),
                {set.cell_width, set.cell_height});
        };
        const quality::CellGridLines s = lines_of(false), w = lines_of(true);
        UNSCOPED_INFO("map seed " << seed << ": straight frames rows " << s.rows << " at "
                                  << s.row_at << ", columns " << s.columns << " at " << s.column_at
                                  << "; wandering rows " << w.rows << " at " << w.row_at
                                  << ", columns " << w.columns << " at " << w.column_at);
        straight += s.worst() / 2, wandering += w.worst() / 2;
    }
    INFO("mean of the stronger: straight " << straight << ", wandering " << wandering);
    CHECK(straight > 1.3);
    CHECK(wandering < straight - 0.08);
}

TEST_CASE("frame patches move the cuts along a wood wall's cell borders off one line",
          "[quality][cell_set][frame_patches][heavy]") {
    // Wood's grain breaks at every upright cell border where the cells cut into their strips
    // (lines along the grid 1.67 and 1.74 at map seeds 1 and 2 without frame patches, about
    // 1.2-1.3 with them, session 35).
    const cv::Mat wood = synth::load_exemplar(
        std::filesystem::path(TILEJET_SOURCE_DIR) / "tests/quality/corpus/wood.png", {});
    double without = 0, with = 0;
    for (const uint64_t seed : {1, 2}) {
        synth::BuildParams p;
        p.seed = seed;
        const auto lines_of = [&](int frame_patches) {
            p.frame_patches = frame_patches;
            const synth::TextureMap set = synth::build_texture_map(wood, p);
            return quality::cell_grid_lines(
                quality::cell_stretch_plane(set, 7, quality::kWideStretch),
                {set.cell_width, set.cell_height});
        };
        const quality::CellGridLines a = lines_of(0), b = lines_of(4);
        UNSCOPED_INFO("map seed " << seed << ": without rows " << a.rows << ", columns "
                                  << a.columns << " at " << a.column_at << "; with rows " << b.rows
                                  << ", columns " << b.columns << " at " << b.column_at);
        without += a.worst() / 2, with += b.worst() / 2;
    }
    INFO("mean of the stronger: without " << without << ", with " << with);
    CHECK(without > 1.5);
    CHECK(with < without - 0.25);
}
