#include <catch2/catch.hpp>
#include <opencv2/core.hpp>

#include "../synth/fixtures.hpp"
#include "tilejet/quality/texture_energy.hpp"
#include "walls.hpp"

using namespace tilejet;

TEST_CASE("texture energy: an exemplar crop is near 0, an unrelated image is high", "[quality]") {
    const cv::Mat& exemplar = test::demo_exemplar();
    const quality::TextureEnergy energy(exemplar, 2);
    // Every 8x8 patch of a crop is an exemplar patch: distance 0 when the search finds it.
    const double crop = energy.measure({exemplar(cv::Rect(13, 29, 150, 120)).clone()}, 5000, 1);
    CHECK(crop < 0.5);
    // Saturated colour noise is nothing like green marble.
    const double noise = energy.measure({test::noise_image({150, 120}, 3)}, 5000, 1);
    CHECK(noise > 20);
    // A blurred crop is in between: the same colours, a different texture.
    cv::Mat flat(120, 150, CV_8UC3, cv::mean(exemplar));
    const double mean_colour = energy.measure({flat}, 2000, 1);
    CHECK(mean_colour > crop + 2);
    CHECK(mean_colour < noise);
}

TEST_CASE("texture completeness: a wall that repeats one corner of the exemplar is incomplete",
          "[quality]") {
    const cv::Mat& exemplar = test::demo_exemplar();
    // Walls of the same area: the exemplar tiled whole, and one 64 px corner of it tiled.
    cv::Mat whole, corner;
    cv::repeat(exemplar, 2, 2, whole);
    cv::repeat(exemplar(cv::Rect(0, 0, 64, 64)), 2 * exemplar.rows / 64, 2 * exemplar.cols / 64,
               corner);
    const auto completeness = [&](const cv::Mat& wall) {
        return quality::TextureEnergy(std::vector<cv::Mat>{wall}, 2, wall.total())
            .measure({exemplar}, 5000, 1);
    };
    const quality::TextureEnergy coherence(exemplar, 2);
    // One way, the corner's wall is nearly as good as the whole exemplar's (only the joins
    // between its copies are not in the exemplar) ...
    const double corner_coherence = coherence.measure({corner}, 5000, 1);
    CHECK(coherence.measure({whole}, 5000, 1) < 0.5);
    // ... the other way, only one of them holds the exemplar.
    CHECK(completeness(whole) < 0.5);
    CHECK(completeness(corner) > 2 * corner_coherence);
}

TEST_CASE("texture energy: several images index as one", "[quality]") {
    const cv::Mat& exemplar = test::demo_exemplar();
    const cv::Mat left = exemplar(cv::Rect(0, 0, exemplar.cols / 2, exemplar.rows)).clone();
    const cv::Mat right =
        exemplar(cv::Rect(exemplar.cols / 2, 0, exemplar.cols / 2, exemplar.rows)).clone();
    const quality::TextureEnergy halves(std::vector<cv::Mat>{left, right}, 2);
    const quality::TextureEnergy only_left(left, 2);
    const cv::Mat from_right = right(cv::Rect(20, 20, 80, 80)).clone();
    CHECK(halves.measure({from_right}, 3000, 1) < 0.5);
    CHECK(only_left.measure({from_right}, 3000, 1) > 1);
    CHECK_THROWS_WITH(quality::TextureEnergy(std::vector<cv::Mat>{}, 1),
                      Catch::Contains("needs an image"));
}

// [heavy]: a million patches indexed, 16 s (left out of the sanitizer pass, tests/CMakeLists.txt).
TEST_CASE("texture completeness: a wall's every position is indexed, wherever the copy lies",
          "[quality][heavy]") {
    // eval's completeness indexes a stretch of wall of 1 Mpx or more. On a coarser grid (every
    // third position, as up to session 25) an exemplar patch copied off that grid had only
    // misaligned neighbours to be compared with: a floor of about 4 under every method's
    // figure on the corpus, far above the differences between them.
    const cv::Mat& exemplar = test::demo_exemplar();
    cv::Mat wall = test::noise_image({1100, 1000}, 5);
    for (const cv::Point at : {cv::Point(101, 53), cv::Point(500, 602)})
        exemplar.copyTo(wall(cv::Rect(at, exemplar.size())));
    const quality::TextureEnergy index(std::vector<cv::Mat>{wall}, 2);
    CHECK(index.measure({exemplar}, 3000, 1) < 0.5);
}
