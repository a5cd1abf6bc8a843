// The grain of an exemplar (its largest structures), which sizes the cells.

#include <catch2/catch.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

#include "grain.hpp"

using namespace tilejet::synth::detail;

namespace {

// Blobs of one size on a grey ground, scattered at random: structures of a known size.
cv::Mat blobs(int side, int radius, std::uint32_t seed) {
    cv::Mat out(side, side, CV_8UC3, cv::Scalar(110, 110, 110));
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> at(0, side - 1), shade(20, 240);
    const int count = side * side / (radius * radius * 6);
    for (int i = 0; i < count; ++i) {
        const int s = shade(rng);
        cv::circle(out, {at(rng), at(rng)}, radius, cv::Scalar(s, s, s), cv::FILLED);
    }
    return out;
}

}  // namespace

TEST_CASE("coarser structures have a larger grain", "[grain]") {
    const double fine = grain_size(blobs(512, 4, 1)), coarse = grain_size(blobs(512, 16, 1));
    CHECK(fine < coarse);
    CHECK(cell_side_for_grain(fine, false, 512) <= cell_side_for_grain(coarse, false, 512));
}

// At 360 dpi a stone's veins are hundreds of px long: a slab scan's cells may hold more of them
// than a small exemplar's, whose build is held to a minute.
TEST_CASE("a slab scan's coarse structures get larger cells than a small exemplar can have",
          "[grain][slab]") {
    const cv::Mat small = blobs(512, 40, 3);
    cv::Mat large;
    cv::resize(small, large, {2048, 2048}, 0, 0, cv::INTER_LINEAR);
    const int small_cell = cell_side_for_grain(grain_size(small), false, 512);
    const int large_cell = cell_side_for_grain(grain_size(large), false, 2048);
    INFO("cells " << small_cell << " px at 512, " << large_cell << " px at 2048");
    CHECK(large_cell > small_cell);
    CHECK(large_cell <= 640);
}

// A slab scan is measured at most 2048 px across: the same structures, scanned at four times
// the resolution, come out four times as large in px.
TEST_CASE("a slab-scan-sized exemplar's grain is that of a smaller copy, scaled", "[grain][slab]") {
    const cv::Mat small = blobs(1024, 8, 2);
    cv::Mat large;
    cv::resize(small, large, {4096, 4096}, 0, 0, cv::INTER_LINEAR);
    const double g_small = grain_size(small), g_large = grain_size(large);
    INFO("grain " << g_small << " px at 1024, " << g_large << " px at 4096");
    CHECK(g_large == Approx(4 * g_small).epsilon(0.15));
}
