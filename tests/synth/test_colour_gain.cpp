// Colour-regularity gain on a brick exemplar with a known lattice.

#include <catch2/catch.hpp>
#include <opencv2/core.hpp>
#include <string>

#include "fixtures.hpp"
#include "tilejet/synth/build.hpp"
#include "tilejet/synth/error.hpp"
#include "tilejet/synth/internal/colour_gain.hpp"
#include "tilejet/synth/lattice.hpp"

using namespace tilejet::synth;

namespace {

// Running bond of 40 x 17 px bricks, each course shifted by half a brick: the test's own
// notion of "the same place in another brick", independent of the code under test.
cv::Point brick_phase(int x, int y) {
    const int course = y / 17;
    return {((x - 20 * course) % 40 + 40) % 40, y % 17};
}

// Variance across bricks at the same place of a brick, averaged over places and channels.
double across_tile_variance(const cv::Mat& rgb) {
    cv::Mat sum(17, 40, CV_64FC3, cv::Scalar::all(0)), sq = sum.clone(),
                                                       n(17, 40, CV_64F, cv::Scalar(0));
    for (int y = 0; y < rgb.rows; ++y)
        for (int x = 0; x < rgb.cols; ++x) {
            const cv::Point p = brick_phase(x, y);
            const cv::Vec3d c = rgb.at<cv::Vec3b>(y, x);
            sum.at<cv::Vec3d>(p) += c;
            sq.at<cv::Vec3d>(p) += c.mul(c);
            n.at<double>(p) += 1;
        }
    double total = 0;
    for (int y = 0; y < 17; ++y)
        for (int x = 0; x < 40; ++x)
            for (int k = 0; k < 3; ++k) {
                const double m = sum.at<cv::Vec3d>(y, x)[k] / n.at<double>(y, x);
                total += sq.at<cv::Vec3d>(y, x)[k] / n.at<double>(y, x) - m * m;
            }
    return total / (17 * 40 * 3);
}

const cv::Mat& brick() {
    static const cv::Mat m =
        tilejet::test::make_lattice_texture({{40, 0}, {20, 17}}, {233, 191}, 8);
    return m;
}

}  // namespace

TEST_CASE("colour gain: 0 makes every brick the mean brick, 1 changes nothing, 2 varies more",
          "[colour_gain]") {
    const Lattice lattice = detect_lattice(brick());
    REQUIRE(tilejet::test::same_lattice(lattice, {{40, 0}, {20, 17}}));
    const double original = across_tile_variance(brick());
    INFO("exemplar's variance across bricks " << original);
    REQUIRE(original > 50);  // the fixture's bricks do differ (sd 14 per channel, noise 6)

    const cv::Mat same = apply_colour_gain(brick(), lattice, 1);
    CHECK(cv::norm(same, brick(), cv::NORM_INF) == 0);

    // Rounding to 8 bits is the only variance left.
    const cv::Mat alike = apply_colour_gain(brick(), lattice, 0);
    CHECK(across_tile_variance(alike) < 0.5);

    const cv::Mat varied = apply_colour_gain(brick(), lattice, 2);
    INFO("gain 2: " << across_tile_variance(varied));
    CHECK(across_tile_variance(varied) > 2 * original);

    const cv::Mat calmer = apply_colour_gain(brick(), lattice, 0.5);
    CHECK(across_tile_variance(calmer) < 0.5 * original);
}

TEST_CASE("colour gain: stochastic exemplars and negative gains are errors", "[colour_gain]") {
    const cv::Mat& marble = tilejet::test::demo_exemplar();
    const Lattice none;  // what detect_lattice reports for marble (test_lattice.cpp)
    CHECK(cv::norm(apply_colour_gain(marble, none, 1), marble, cv::NORM_INF) == 0);
    CHECK_THROWS_WITH(apply_colour_gain(marble, none, 0.5),
                      Catch::Contains("--colour-gain") && Catch::Contains("stochastic"));
    CHECK_THROWS_WITH(apply_colour_gain(brick(), detect_lattice(brick()), -1),
                      Catch::Contains("--colour-gain"));

    // Courses have no tiles to compare: joints fall anywhere along them.
    const cv::Mat courses = tilejet::test::make_course_texture(16.6, {200, 200}, 1);
    const Lattice rows = detect_lattice(courses);
    REQUIRE(rows.kind == LatticeKind::Courses);
    CHECK(cv::norm(apply_colour_gain(courses, rows, 1), courses, cv::NORM_INF) == 0);
    CHECK_THROWS_WITH(apply_colour_gain(courses, rows, 0.5),
                      Catch::Contains("--colour-gain") && Catch::Contains("courses"));

    BuildParams p;
    p.colour_gain = 2;
    CHECK_THROWS_WITH(build_texture_map(marble, p),
                      Catch::Contains("--colour-gain") && Catch::Contains("stochastic"));
}

TEST_CASE("colour gain: map build takes its source from the rebuilt exemplar",
          "[colour_gain][build][heavy]") {
    BuildParams p;
    p.corner_colours = 1;
    p.cell_size = 64;  // the lattice rounds it to whole bricks; the exemplar is the source
    p.patches = 20;
    p.candidates = 120;
    p.colour_gain = 0;
    const TextureMap map = build_texture_map(brick(), p);
    REQUIRE(map.source.size() == brick().size());
    CHECK(across_tile_variance(map.source) < 0.5);
}
