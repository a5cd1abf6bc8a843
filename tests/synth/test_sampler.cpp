// Region rendering against per-pixel sampling, and determinism over threads.

#include <catch2/catch.hpp>
#include <opencv2/core.hpp>
#include <random>

#include "fixtures.hpp"
#include "tilejet/synth/sampler.hpp"

using namespace tilejet::synth;
using tilejet::test::same_bytes;
using tilejet::test::small_map;

TEST_CASE("region rendering gives the same bytes on 1, 2 and 4 threads", "[sampler]") {
    const TextureMap& map = small_map();
    for (const Region region :
         {Region{0, 0, 517, 389}, Region{-(int64_t(1) << 31), 12345, 300, 301},
          Region{(int64_t(1) << 31) - 640, -(int64_t(1) << 31), 640, 3}}) {
        const cv::Mat one = render_region(map, 42, region, 1);
        REQUIRE(same_bytes(one, render_region(map, 42, region, 2)));
        REQUIRE(same_bytes(one, render_region(map, 42, region, 4)));
        REQUIRE(same_bytes(one, render_region(map, 42, region, 7)));
    }
}

TEST_CASE("every pixel of a region equals Sampler::sample", "[sampler]") {
    const TextureMap& map = small_map();
    const int64_t big = int64_t(1) << 31;
    for (const Region region : {Region{-150, -90, 300, 180}, Region{big - 200, big - 100, 200, 100},
                                Region{-big, -big, 200, 100}, Region{-big, big - 64, 130, 64}}) {
        const cv::Mat out = render_region(map, 9, region, 2);
        INFO("region at " << region.x << "," << region.y);
        REQUIRE(tilejet::test::pixels_unlike_sampler(map, 9, region, out) == 0);
    }
}

TEST_CASE("sample equals region render at random points, huge and negative included", "[sampler]") {
    const TextureMap& map = small_map();
    std::mt19937_64 rng(5);
    std::uniform_int_distribution<int64_t> coord(-(int64_t(1) << 31), (int64_t(1) << 31) - 1);
    for (int n = 0; n < 300; ++n) {
        const uint64_t seed = rng();
        const int64_t x = coord(rng), y = coord(rng);
        // Render a small window around the point, then sample it with a fresh sampler so that
        // nothing is shared between the two paths.
        const Region window{x - 3, y - 2, 7, 5};
        const cv::Mat out = render_region(map, seed, window, 1);
        Sampler sampler(map, seed);
        const cv::Vec3b r = out.at<cv::Vec3b>(2, 3);
        REQUIRE(sampler.sample(x, y) == Rgb{r[0], r[1], r[2]});
    }
}

TEST_CASE(
    "a wide region, built strip by strip, equals Sampler::sample at any stride and "
    "alignment",
    "[sampler]") {
    // Wide enough that a cache-sized strip holds only a few rows, so patches cross strip
    // borders; written one byte off alignment and with padding after each row.
    const TextureMap& map = small_map();
    const Region region{-4321, 876, 9000, 37};
    const size_t row = size_t(region.width) * 3, stride = row + 5;
    std::vector<uint8_t> buffer(1 + stride * size_t(region.height), 0xA5);
    render_region(map, 11, region, buffer.data() + 1, stride, 2);
    Sampler sampler(map, 11);
    size_t mismatches = 0;
    for (int y = 0; y < region.height; ++y) {
        const uint8_t* line = buffer.data() + 1 + size_t(y) * stride;
        for (int x = 0; x < region.width; ++x) {
            const Rgb s = sampler.sample(region.x + x, region.y + y);
            mismatches += !(s == Rgb{line[3 * x], line[3 * x + 1], line[3 * x + 2]});
        }
        // The padding is not the region's: it keeps what it had.
        for (size_t k = row; k < stride; ++k)
            mismatches += line[k] != 0xA5;
    }
    REQUIRE(buffer[0] == 0xA5);
    REQUIRE(mismatches == 0);
}

TEST_CASE("a region rendered in pieces equals the region rendered whole", "[sampler]") {
    const TextureMap& map = small_map();
    const Region whole{-777, 1234, 400, 300};
    const cv::Mat all = render_region(map, 3, whole, 2);
    const cv::Mat left = render_region(map, 3, {whole.x, whole.y, 123, 300}, 1);
    const cv::Mat right = render_region(map, 3, {whole.x + 123, whole.y, 277, 300}, 1);
    cv::Mat joined;
    cv::hconcat(left, right, joined);
    REQUIRE(same_bytes(all, joined));
}

TEST_CASE("different seeds give different planes, the same seed the same plane", "[sampler]") {
    const TextureMap& map = small_map();
    const Region region{0, 0, 256, 256};
    REQUIRE(same_bytes(render_region(map, 1, region), render_region(map, 1, region)));
    REQUIRE_FALSE(same_bytes(render_region(map, 1, region), render_region(map, 2, region)));
}

TEST_CASE("points and regions outside the plane are refused", "[sampler]") {
    const TextureMap& map = small_map();
    Sampler sampler(map, 1);
    REQUIRE_THROWS_AS(sampler.sample(int64_t(1) << 41, 0), SynthError);
    REQUIRE_THROWS_AS(render_region(map, 1, Region{0, -(int64_t(1) << 41), 4, 4}), SynthError);
    REQUIRE_THROWS_AS(render_region(map, 1, Region{0, 0, -4, 4}), SynthError);
}
