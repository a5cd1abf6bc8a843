// A cell set's plane against the lines along the cell grid (cell_grid_lines.hpp): with its
// frames' depth and its blocks' joints the same in every image, a wall of the corpus's slate
// showed its cells as squares; wandering, image by image, far less.

#include <catch2/catch.hpp>
#include <filesystem>
#include <functional>

#include "tilejet/quality/cell_grid_lines.hpp"
#include "tilejet/quality/cell_stretch.hpp"
#include "tilejet/synth/build.hpp"
#include "tilejet/synth/exemplar.hpp"

using namespace tilejet;

namespace {

struct LinesPair {
    double before = 0, after = 0;  // mean over the map seeds of the stronger of rows and columns
};

// One way of building a set: the defaults (scripts/corpus-eval's 256 px cells) set up, and the
// corner colours and image count it must come out with.
struct Way {
    std::function<void(synth::BuildParams&)> set_up;
    int corner_colours;
    size_t images;
};

// The lines along the grid of a corpus design's set built two ways, averaged over map seeds 1
// and 2: one says little, the figure swings by a tenth or so from seed to seed.
LinesPair lines_two_ways(const char* design, const Way& before, const Way& after) {
    const cv::Mat exemplar = synth::load_exemplar(
        std::filesystem::path(TILEJET_SOURCE_DIR) / "tests/quality/corpus" / design, {});
    LinesPair mean;
    for (const uint64_t seed : {1, 2}) {
        const auto lines_of = [&](const Way& way) {
            synth::BuildParams p;
            p.seed = seed;
            p.corner_colours = way.corner_colours;
            way.set_up(p);
            const synth::TextureMap set = synth::build_texture_map(exemplar, p);
            REQUIRE(set.corner_colours == way.corner_colours);
            REQUIRE(set.cell_images.size() == way.images);
            return quality::cell_grid_lines(
                quality::cell_stretch_plane(set, 7, quality::kWideStretch),
                {set.cell_width, set.cell_height});
        };
        const quality::CellGridLines a = lines_of(before), b = lines_of(after);
        UNSCOPED_INFO(design << ", map seed " << seed << ": before rows " << a.rows << " at "
                             << a.row_at << ", columns " << a.columns << " at " << a.column_at
                             << "; after rows " << b.rows << " at " << b.row_at << ", columns "
                             << b.columns << " at " << b.column_at);
        mean.before += a.worst() / 2, mean.after += b.worst() / 2;
    }
    return mean;
}

// As the sets were measured before three colours were the default (sessions 32-35): 2 colours,
// two variants, 36 images.
Way two_colours(std::function<void(synth::BuildParams&)> set_up) {
    return {std::move(set_up), 2, 36};
}

}  // namespace

TEST_CASE("a set's cells show fewer lines along the grid than straight frames drew",
          "[quality][cell_set][heavy]") {
    const LinesPair lines = lines_two_ways(
        "slate.png",
        // Blocks by seam cost alone, as when wandering was measured: weighing tone steps too
        // (session 41) draws straight frames' lines fainter as well (1.33 with two colours).
        two_colours(
            [](synth::BuildParams& p) { p.wandering_frames = false, p.weigh_tone_steps = false; }),
        two_colours(
            [](synth::BuildParams& p) { p.wandering_frames = true, p.weigh_tone_steps = false; }));
    INFO("mean of the stronger: straight " << lines.before << ", wandering " << lines.after);
    CHECK(lines.before > 1.3);
    CHECK(lines.after < lines.before - 0.08);
}

TEST_CASE("weighing each block's tone step draws fainter lines along slate's cell grid",
          "[quality][cell_set][heavy]") {
    // Slate's lighter and darker plates: a block's cut that matches its frame detail for detail
    // can still leave a step of tone along every border (session 41).
    const LinesPair lines = lines_two_ways(
        "slate.png", {[](synth::BuildParams& p) { p.weigh_tone_steps = false; }, 3, 168},
        {[](synth::BuildParams& p) { p.weigh_tone_steps = true; }, 3, 168});
    INFO("mean of the stronger: by seam cost alone " << lines.before << ", tone steps weighed "
                                                     << lines.after);
    CHECK(lines.after < lines.before - 0.04);
}

TEST_CASE("frame patches move the cuts along a wood wall's cell borders off one line",
          "[quality][cell_set][frame_patches][heavy]") {
    // Wood's grain breaks at every upright cell border where the cells cut into their strips
    // (lines along the grid 1.67 and 1.74 at map seeds 1 and 2 without frame patches, about
    // 1.2-1.3 with them, session 35).
    const LinesPair lines =
        lines_two_ways("wood.png", two_colours([](synth::BuildParams& p) { p.frame_patches = 0; }),
                       two_colours([](synth::BuildParams& p) { p.frame_patches = 4; }));
    INFO("mean of the stronger: without " << lines.before << ", with " << lines.after);
    CHECK(lines.before > 1.5);
    CHECK(lines.after < lines.before - 0.25);
}

TEST_CASE(
    "four corner colours with strips an eighth of the cell draw fainter lines along wood's "
    "cell grid than three with a tenth",
    "[quality][cell_set][heavy]") {
    // Wood's grain breaks at every upright cell border, where a band of the edge's strip shows
    // between two cuts. Four colours (256 images of one variant, a strip at one edge in 16)
    // let the strips be wider without showing more often, and the cuts into them wander over
    // more of the cell (session 42). Measured: 1.70 -> 1.64 on the mean of the stronger over
    // map seeds 1 and 2, nearly all of it at map seed 1 (eval's lines 1.69 -> 1.54, 1.68 ->
    // 1.65): a step, not the fix.
    // Without frame patches, which wood gets by default since session 43 (measured above).
    const auto no_frame_patches = [](synth::BuildParams& p) { p.frame_patches = 0; };
    const LinesPair lines =
        lines_two_ways("wood.png", {no_frame_patches, 3, 168}, {no_frame_patches, 4, 256});
    INFO("mean of the stronger: three colours " << lines.before << ", four " << lines.after);
    CHECK(lines.after < lines.before - 0.04);
}
