#include <catch2/catch.hpp>
#include <opencv2/core.hpp>

#include "../synth/fixtures.hpp"
#include "tilejet/quality/cell_place_energy.hpp"
#include "tilejet/synth/sampler.hpp"

using namespace tilejet;

namespace {

// A plane of 4 x 4 cells of `cell` px, each a crop of the exemplar from its own place: every
// cell border is a seam between unrelated texture, the insides are the exemplar's own.
cv::Mat cells_from_elsewhere(const cv::Mat& exemplar, int cell) {
    cv::Mat plane(4 * cell, 4 * cell, CV_8UC3);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            const cv::Point from((37 * (i + 4 * j)) % (exemplar.cols - cell),
                                 (53 * (i + 4 * j) + 11 * i) % (exemplar.rows - cell));
            exemplar(cv::Rect(from, cv::Size(cell, cell)))
                .copyTo(plane(cv::Rect(i * cell, j * cell, cell, cell)));
        }
    return plane;
}

}  // namespace

TEST_CASE("texture coherence by place: seams along the cell borders show there, not inside",
          "[quality]") {
    const cv::Mat& exemplar = test::demo_exemplar();
    const quality::TextureEnergy energy(exemplar, 2);
    const int cell = 60;
    const quality::CellPlaceEnergy seams = quality::cell_place_energy(
        cells_from_elsewhere(exemplar, cell), {cell, cell}, energy, 3000, 1);
    REQUIRE(seams.band == 6);
    INFO("border " << seams.border << ", inside " << seams.inside);
    CHECK(seams.inside < 0.5);  // exemplar patches: found at distance 0 or near it
    CHECK(seams.border > 4 * std::max(seams.inside, 0.25));

    // One crop of the exemplar laid over the same cells: no seam anywhere, both low alike.
    const cv::Mat whole = exemplar(cv::Rect(0, 0, 4 * cell, 4 * cell)).clone();
    const quality::CellPlaceEnergy none =
        quality::cell_place_energy(whole, {cell, cell}, energy, 3000, 1);
    INFO("no seam: border " << none.border << ", inside " << none.inside);
    CHECK(none.border < 0.5);
    CHECK(none.inside < 0.5);
}

TEST_CASE("texture coherence by place: a map's plane is measured from a cell corner", "[quality]") {
    const synth::TextureMap& map = test::small_map();
    const quality::TextureEnergy energy(test::demo_exemplar(), 2);
    const quality::CellPlaceEnergy r = quality::cell_place_energy(map, 7, energy, 2000, 2);
    // The same measure on the plane rendered by hand from the origin.
    const cv::Mat plane =
        synth::render_region(map, 7, {0, 0, 8 * map.cell_width, 8 * map.cell_height}, 2);
    const quality::CellPlaceEnergy by_hand =
        quality::cell_place_energy(plane, {map.cell_width, map.cell_height}, energy, 2000, 7);
    CHECK(r.band == std::max(1, std::min(map.cell_width, map.cell_height) / 10));
    CHECK(r.border == by_hand.border);
    CHECK(r.inside == by_hand.inside);
    CHECK(r.border > 0);
}

TEST_CASE("texture coherence by place: a plane smaller than a patch is refused", "[quality]") {
    const quality::TextureEnergy energy(test::demo_exemplar(), 1);
    CHECK_THROWS(quality::cell_place_energy(cv::Mat(4, 4, CV_8UC3, cv::Scalar::all(0)), {32, 32},
                                            energy, 10, 1));
    CHECK_THROWS(quality::cell_place_energy(cv::Mat(64, 64, CV_8UC3, cv::Scalar::all(0)), {0, 32},
                                            energy, 10, 1));
}
