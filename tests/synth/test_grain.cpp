// The grain of an exemplar (its largest structures), which sizes the cells.

#include <catch2/catch.hpp>
#include <cmath>
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

namespace {

// Parallel waves `period` px apart across the direction `angle` (radians), with noise over them:
// a grain that runs one way.
cv::Mat waves(int side, double angle, double period, std::uint32_t seed) {
    cv::Mat out(side, side, CV_8UC3);
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0, 12);
    const double cx = std::cos(angle), cy = std::sin(angle);
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
            const double v =
                128 + 60 * std::sin(2 * CV_PI * (x * cx + y * cy) / period) + noise(rng);
            const auto c = cv::saturate_cast<uint8_t>(v);
            out.at<cv::Vec3b>(y, x) = {c, uint8_t(c * 3 / 4), uint8_t(c / 2)};
        }
    return out;
}

}  // namespace

TEST_CASE("a grain that runs one way is aligned whatever its direction, blobs are not", "[grain]") {
    for (const double angle : {0.0, CV_PI / 2, CV_PI / 5}) {
        INFO("waves across " << angle << " rad");
        CHECK(grain_alignment(waves(256, angle, 9, 1)) > 0.7);
    }
    CHECK(grain_alignment(blobs(256, 6, 1)) < 0.2);
    CHECK(grain_alignment(cv::Mat(64, 64, CV_8UC3, cv::Scalar::all(90))) == 0);
    // A slab scan's is measured on a smaller copy (analysis_size.hpp), to the same answer.
    CHECK(grain_alignment(waves(2600, CV_PI / 2, 40, 2)) > 0.7);
}

// Frame patches go on the cell edges across a grain (build.cpp): its direction must come out
// square to the waves' gradient whichever way they run.
TEST_CASE("a grain's direction runs square to the way its waves vary", "[grain]") {
    const auto diff = [](double a, double b) {  // between directions, modulo 180 degrees
        const double d = std::fmod(std::abs(a - b), 180.0);
        return std::min(d, 180 - d);
    };
    for (const double across : {0.0, 36.0, 90.0, 150.0}) {
        const GrainDirection grain = grain_direction(waves(256, across * CV_PI / 180, 9, 3));
        INFO("waves varying along " << across << " degrees: grain at " << grain.degrees);
        CHECK(grain.alignment > 0.7);
        CHECK(grain.degrees >= 0);
        CHECK(grain.degrees < 180);
        CHECK(diff(grain.degrees, across + 90) < 3);
    }
}
