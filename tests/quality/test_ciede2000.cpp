#include <catch2/catch.hpp>

#include "tilejet/quality/colour_match.hpp"
#include "walls.hpp"

using namespace tilejet;

// Pairs and expected differences from Sharma, Wu and Dalal (2005), table 1.
TEST_CASE("CIEDE2000 matches the published test data", "[quality]") {
    CHECK(colour::ciede2000({50, 2.6772, -79.7751}, {50, 0, -82.7485}) ==
          Approx(2.0425).margin(1e-4));
    CHECK(colour::ciede2000({50, 0, 0}, {50, -1, 2}) == Approx(2.3669).margin(1e-4));
    CHECK(colour::ciede2000({50, 2.5, 0}, {73, 25, -18}) == Approx(27.1492).margin(1e-4));
    CHECK(colour::ciede2000({60.2574, -34.0099, 36.2677}, {60.4626, -34.1751, 39.4387}) ==
          Approx(1.2644).margin(1e-4));
    // The pairs that test the mean hue across 0°/360° (Sharma's 9, 11 and 13), where
    // implementations go wrong.
    CHECK(colour::ciede2000({50, 2.49, -0.001}, {50, -2.49, 0.0009}) ==
          Approx(7.1792).margin(1e-4));
    CHECK(colour::ciede2000({50, 2.49, -0.001}, {50, -2.49, 0.0011}) ==
          Approx(7.2195).margin(1e-4));
    CHECK(colour::ciede2000({50, -0.001, 2.49}, {50, 0.0009, -2.49}) ==
          Approx(4.8045).margin(1e-4));
    CHECK(colour::ciede2000({50, 10, 10}, {50, 10, 10}) == 0);
}

TEST_CASE("colour match: same pixels give 0, a shifted wall does not", "[quality]") {
    const cv::Mat a = test::noise_image({64, 64}, 5);
    const auto ex = quality::lab_statistics({a});
    const auto same = quality::compare_colour(ex, quality::lab_statistics({a.clone(), a.clone()}));
    CHECK(same.mean_delta_e2000 == Approx(0).margin(1e-9));
    CHECK(same.histogram_distance == Approx(0).margin(1e-6));
    cv::Mat dark = a * 0.5;
    const auto shifted = quality::compare_colour(ex, quality::lab_statistics({dark}));
    CHECK(shifted.mean_delta_e2000 > 10);
    CHECK(shifted.histogram_distance > 0.2);
}

// The tails: a wall of the exemplar's pixels holds the exemplar's share beyond its lightest and
// darkest 5 %; a wall of its calm middle holds none; a wall with a quarter of white pixels holds
// at least that quarter in the light tail.
TEST_CASE("lightness tails: the exemplar's own pixels keep 5 %, a calm wall none", "[quality]") {
    cv::Mat ramp(100, 256, CV_8UC3);  // every grey level equally often
    for (int y = 0; y < ramp.rows; ++y)
        for (int x = 0; x < ramp.cols; ++x)
            ramp.at<cv::Vec3b>(y, x) = cv::Vec3b::all(uint8_t(x));
    const auto ex = quality::lab_statistics({ramp});
    const double lo = quality::lightness_quantile(ex, 0.05),
                 hi = quality::lightness_quantile(ex, 0.95);
    CHECK(lo < hi);
    CHECK(quality::share_darker(ex, lo) == Approx(0.05).margin(0.002));
    CHECK(quality::share_lighter(ex, hi) == Approx(0.05).margin(0.002));

    const auto same = quality::compare_colour(ex, quality::lab_statistics({ramp.clone()}));
    CHECK(same.light_tail == Approx(quality::kTailShare).margin(0.002));
    CHECK(same.dark_tail == Approx(quality::kTailShare).margin(0.002));

    const cv::Mat calm = ramp.colRange(64, 192).clone();  // the middle half of the grey levels
    const auto calm_match = quality::compare_colour(ex, quality::lab_statistics({calm}));
    CHECK(calm_match.light_tail == 0);
    CHECK(calm_match.dark_tail == 0);
    // The mean colour hardly tells the calm wall apart: under a just-noticeable difference.
    CHECK(calm_match.mean_delta_e2000 < 2.3);

    cv::Mat veined = calm.clone();
    veined.rowRange(0, veined.rows / 4).setTo(cv::Scalar::all(255));
    const auto veined_match = quality::compare_colour(ex, quality::lab_statistics({veined}));
    CHECK(veined_match.light_tail >= 0.25 - 1e-9);
    CHECK(veined_match.dark_tail == 0);
}
