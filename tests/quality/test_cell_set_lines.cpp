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
