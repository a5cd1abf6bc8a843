#include <catch2/catch.hpp>
#include <opencv2/core.hpp>

#include "../synth/fixtures.hpp"
#include "tilejet/synth/texture_energy.hpp"
#include "walls.hpp"

using namespace tilejet;

TEST_CASE("texture energy: an exemplar crop is near 0, an unrelated image is high", "[quality]") {
    const cv::Mat& exemplar = test::demo_exemplar();
    const synth::TextureEnergy energy(exemplar, 2);
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
