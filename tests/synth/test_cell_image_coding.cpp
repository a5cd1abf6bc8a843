// Cell images coded against the map's source: what is decoded is what was coded, pixel for pixel,
// a mosaic of source windows codes to residuals that are almost all zero, and a damaged code is
// refused with a message naming what is wrong.

#include <catch2/catch.hpp>
#include <opencv2/core.hpp>

#include "cell_image_coding.hpp"
#include "fixtures.hpp"
#include "tilejet/synth/map_file.hpp"

using namespace tilejet::synth;
using namespace tilejet::synth::detail;
using Catch::Matchers::Contains;
using tilejet::test::same_bytes;

namespace {

cv::Mat noise(cv::Size size, uint64_t seed) {
    cv::Mat m(size, CV_8UC3);
    cv::RNG rng(seed);
    rng.fill(m, cv::RNG::UNIFORM, 0, 256);
    return m;
}

// A cell image as a set makes them: windows of the source side by side, from anywhere in it, one
// band where two of them were blended, a few stray pixels. The windows meet on the coding
// blocks' grid, so that every pixel not blended or stray has a block displacement that predicts
// it (where windows meet inside a block, only one of them can).
cv::Mat mosaic_of(const cv::Mat& source, cv::Size cell, uint64_t seed) {
    cv::RNG rng(seed);
    cv::Mat out(cell, CV_8UC3);
    for (int y = 0; y < cell.height; y += 3 * kCodingBlock)
        for (int x = 0; x < cell.width; x += 4 * kCodingBlock) {
            const cv::Rect to(x, y, std::min(4 * kCodingBlock, cell.width - x),
                              std::min(3 * kCodingBlock, cell.height - y));
            const cv::Point from(rng.uniform(0, source.cols - to.width + 1),
                                 rng.uniform(0, source.rows - to.height + 1));
            source(cv::Rect(from, to.size())).copyTo(out(to));
        }
    cv::Mat band = out(cv::Rect(0, cell.height / 2, cell.width, 3));
    cv::addWeighted(band, 0.5, source(cv::Rect(0, 0, cell.width, 3)), 0.5, 0, band);
    for (int i = 0; i < 20; ++i)
        out.at<cv::Vec3b>(rng.uniform(0, cell.height), rng.uniform(0, cell.width)) =
            cv::Vec3b(uint8_t(rng.uniform(0, 256)), 7, 200);
    return out;
}

size_t nonzero_residual_bytes(const std::vector<uint8_t>& coded, cv::Size cell) {
    const size_t blocks = size_t((cell.width + kCodingBlock - 1) / kCodingBlock) *
                          size_t((cell.height + kCodingBlock - 1) / kCodingBlock);
    return size_t(std::count_if(coded.begin() + 8 + std::ptrdiff_t(4 * blocks), coded.end(),
                                [](uint8_t b) { return b != 0; }));
}

void put_i16(std::vector<uint8_t>& coded, size_t at, int16_t v) {
    coded[at] = uint8_t(uint16_t(v)), coded[at + 1] = uint8_t(uint16_t(v) >> 8);
}

}  // namespace

TEST_CASE("cell images coded against the source decode to the very same pixels", "[coding]") {
    const cv::Mat source = noise({150, 110}, 1);
    const cv::Size cell(70, 61);  // no multiple of the coding block: partial blocks at the edges
    std::vector<cv::Mat> cells;
    for (uint64_t s = 0; s < 5; ++s)
        cells.push_back(mosaic_of(source, cell, s));
    cells.push_back(noise(cell, 99));                             // nothing of the source
    cells.push_back(cv::Mat(cell, CV_8UC3, cv::Scalar::all(0)));  // all zero
    const auto coded = code_cell_images(cells, source);
    REQUIRE(coded.size() == cells.size());
    for (size_t t = 0; t < cells.size(); ++t) {
        INFO("image " << t);
        REQUIRE(same_bytes(decode_cell_image(coded[t], source, cell, "test"), cells[t]));
    }
    // The mosaics' residuals are zero but where they were blended or touched up: the band's 3
    // rows of 70 px and the 20 strays, 3 bytes each.
    const size_t all = size_t(cell.area()) * 3;
    for (size_t t = 0; t < 5; ++t) {
        INFO("image " << t);
        CHECK(nonzero_residual_bytes(coded[t], cell) <= 3 * (3 * 70 + 20));
    }
    CHECK(nonzero_residual_bytes(coded[5], cell) > all * 9 / 10);
    // The same bytes again, whatever the run.
    REQUIRE(code_cell_images(cells, source) == coded);
}

TEST_CASE("a cell image's code that is damaged is refused, saying what is wrong", "[coding]") {
    const cv::Mat source = noise({64, 64}, 2);
    const cv::Size cell(24, 16);
    const std::vector<uint8_t> good =
        code_cell_images(std::vector{mosaic_of(source, cell, 3)}, source).front();
    REQUIRE_NOTHROW(decode_cell_image(good, source, cell, "CELL[3]"));
    SECTION("another size than the cell's") {
        REQUIRE_THROWS_WITH(decode_cell_image(good, source, {24, 24}, "CELL[3]"),
                            Contains("CELL[3]") && Contains("24x16 differs from the cell size"));
    }
    SECTION("truncated, or with bytes to spare") {
        for (size_t n : {size_t(0), size_t(6), size_t(20), good.size() - 1}) {
            const std::vector<uint8_t> part(good.begin(), good.begin() + std::ptrdiff_t(n));
            REQUIRE_THROWS_WITH(decode_cell_image(part, source, cell, "CELL[3]"),
                                Contains("CELL[3]"));
        }
        std::vector<uint8_t> more = good;
        more.push_back(0);
        REQUIRE_THROWS_WITH(decode_cell_image(more, source, cell, "CELL[3]"),
                            Contains("bytes of displacements and residuals"));
    }
    SECTION("a block copying from outside the source") {
        // The second block (8,0): displaced 60 px right its window ends 4 px past the source.
        for (const auto& [dx, dy] : {std::pair<int16_t, int16_t>{60, 0},
                                     {0, 60},
                                     {-9, 0},
                                     {kNoPrediction, 0},
                                     {0, kNoPrediction}}) {
            std::vector<uint8_t> bad = good;
            put_i16(bad, 8 + 4, dx), put_i16(bad, 8 + 6, dy);
            REQUIRE_THROWS_WITH(decode_cell_image(bad, source, cell, "CELL[3]"),
                                Contains("block 1,0 copies from outside the source"));
        }
        // Just inside is accepted.
        std::vector<uint8_t> edge = good;
        put_i16(edge, 8 + 4, 64 - 16), put_i16(edge, 8 + 6, 64 - 8);
        REQUIRE_NOTHROW(decode_cell_image(edge, source, cell, "CELL[3]"));
    }
}

TEST_CASE("a map stored against its source keeps its id and pixels in fewer bytes", "[coding]") {
    // One cell image that is a mosaic of a source of noise: zlib finds nothing to share between
    // them; coded, the cell costs its blend and strays.
    TextureMap map;
    map.source = noise({150, 110}, 4);
    map.cell_width = map.cell_height = 128;
    map.cell_images.push_back({mosaic_of(map.source, {128, 128}, 5), {}, {}});
    assign_map_id(map);
    const std::vector<uint8_t> plain = encode_texture_map(map);
    map.cell_storage = TextureMap::CellStorage::against_source;
    const std::vector<uint8_t> coded = encode_texture_map(map);
    CHECK(plain[8] == 2);  // format version
    CHECK(coded[8] == 4);
    // What the cell image costs either way: the file less that of the same map with a blank cell.
    TextureMap blank = map;
    blank.cell_images.front().pixels = cv::Mat(128, 128, CV_8UC3, cv::Scalar::all(0));
    const size_t rest = encode_texture_map(blank).size();
    REQUIRE(plain.size() > rest + 128 * 128);
    CHECK(coded.size() - rest < (plain.size() - rest) / 8);
    const TextureMap back = decode_texture_map(coded, "coded");
    REQUIRE(back.id == map.id);
    REQUIRE(back.cell_storage == TextureMap::CellStorage::against_source);
    REQUIRE(same_bytes(back.cell_images.front().pixels, map.cell_images.front().pixels));
    // Saved again it stays coded: the same bytes.
    REQUIRE(encode_texture_map(back) == coded);
    // And the plain file loads as before, its storage known.
    REQUIRE(decode_texture_map(plain, "plain").cell_storage == TextureMap::CellStorage::pixels);
}
