#include <catch2/catch.hpp>

#include "tilejet/quality/repetition.hpp"
#include "walls.hpp"

using namespace tilejet;

namespace {

double share_at(const quality::Repetition& r, int size) {
    for (const auto& p : r.curve)
        if (p.size == size) return p.share;
    FAIL("no curve point for " << size);
    return -1;
}

}  // namespace

TEST_CASE("a wall of identical tiles repeats at the tile size and every pair shares", "[quality]") {
    const cv::Mat tile = test::noise_image({128, 128}, 1);
    const quality::Wall wall = test::wall_of({tile, tile, tile, tile, tile, tile}, 3);
    const quality::Repetition r = quality::measure_repetition(wall, 2);
    REQUIRE(r.curve.size() == 4);  // 16, 32, 64, 128: up to the tile size
    for (const auto& p : r.curve)
        CHECK(p.share == 1.0);
    CHECK(r.scale == 128);
    CHECK(r.tile_pairs_sharing == 1.0);
}

TEST_CASE("white noise has no repeated window at all", "[quality]") {
    std::vector<cv::Mat> tiles;
    for (uint32_t k = 0; k < 8; ++k)
        tiles.push_back(test::noise_image({96, 80}, 100 + k));
    const quality::Repetition r = quality::measure_repetition(test::wall_of(tiles, 4), 2);
    REQUIRE(r.curve.size() == 3);  // 16, 32, 64 fit in 80 px
    for (const auto& p : r.curve)
        CHECK(p.share == 0.0);
    CHECK(r.scale == 0);
    CHECK(r.tile_pairs_sharing == 0.0);
}

TEST_CASE("a planted copy is found at any offset, and covers exactly its area", "[quality]") {
    std::vector<cv::Mat> tiles;
    for (uint32_t k = 0; k < 4; ++k)
        tiles.push_back(test::noise_image({128, 128}, 200 + k));
    // A 44x44 block of tile 0 also appears in tile 2 at an unrelated, odd offset.
    tiles[0](cv::Rect(5, 7, 44, 44)).copyTo(tiles[2](cv::Rect(61, 30, 44, 44)));
    const quality::Repetition r = quality::measure_repetition(test::wall_of(tiles, 2), 2);
    const double area = 2.0 * 44 * 44 / (4.0 * 128 * 128);  // both copies: 5.9% of the wall
    CHECK(share_at(r, 16) == Approx(area));
    CHECK(share_at(r, 32) == Approx(area));
    CHECK(share_at(r, 64) == 0.0);
    CHECK(r.scale == 32);                               // above the 5% line up to 32, nothing at 64
    CHECK(r.heat[0].at<uint8_t>(7 + 20, 5 + 20) == 2);  // the largest repeated size: 32
    CHECK(r.heat[0].at<uint8_t>(100, 100) == 0);
    CHECK(r.tile_pairs_sharing == 0.0);  // 44x44 is less than a quarter tile (64x64)
}

TEST_CASE("tiles cropped from one canvas share a quarter tile when they overlap enough",
          "[quality]") {
    const cv::Mat canvas = test::noise_image({400, 400}, 7);
    // Tile 0 and tile 1 overlap by 70x80 px (more than 64x64), tile 2 overlaps tile 0 by
    // 60x128 (a thinner strip: no 64x64 square fits), tile 3 is far from all.
    const std::vector<cv::Rect> crops = {
        {0, 0, 128, 128}, {58, 48, 128, 128}, {68, 0, 128, 128}, {260, 260, 128, 128}};
    std::vector<cv::Mat> tiles;
    for (const cv::Rect& c : crops)
        tiles.push_back(canvas(c).clone());
    const quality::Repetition r = quality::measure_repetition(test::wall_of(tiles, 2), 2);
    CHECK(r.shared_window == cv::Size(64, 64));
    // Pairs (0,1): 70x80 overlap; (1,2): |dx| 10, |dy| 48 -> 118x80 overlap; (0,2): 60x128.
    CHECK(r.tile_pairs_sharing == Approx(2.0 / 6.0));
}
