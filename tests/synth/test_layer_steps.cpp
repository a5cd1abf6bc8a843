// Tone steps where a canvas's layers of different kinds meet, removed in the gradient domain
// (layer_steps.hpp): the step goes, the fixed pixels and each layer's own detail stay.

#include <catch2/catch.hpp>
#include <cmath>
#include <opencv2/core.hpp>

#include "layer_steps.hpp"

using namespace tilejet::synth::detail;

namespace {

constexpr int kSide = 64, kCut = 30;  // the canvas, and its first column of the light copy

// A grainy image, and the same grain `offset` levels lighter.
struct TwoCopies {
    cv::Mat dark, light;
    explicit TwoCopies(int offset) {
        dark.create(kSide, kSide, CV_8UC3);
        cv::RNG rng(7);
        rng.fill(dark, cv::RNG::UNIFORM, 60, 120);
        light = dark + cv::Scalar::all(offset);
    }
};

// Left of column kCut the dark copy (layer 0), from it on the light one (layer 1); the outer
// pixel ring fixed.
struct SteppedCanvas {
    cv::Mat rgb, layer_of, fixed;
    std::vector<CanvasLayer> layers;
    SteppedCanvas(const TwoCopies& copies, int right_kind) {
        rgb = copies.dark.clone();
        copies.light.colRange(kCut, kSide).copyTo(rgb.colRange(kCut, kSide));
        layer_of = cv::Mat(rgb.size(), CV_32S, cv::Scalar(0));
        layer_of.colRange(kCut, kSide).setTo(1);
        fixed = cv::Mat(rgb.size(), CV_8U, cv::Scalar(255));
        fixed(cv::Rect(1, 1, kSide - 2, kSide - 2)).setTo(0);
        layers = {{&copies.dark, {0, 0}, {0, 0, kSide, kSide}, 0},
                  {&copies.light, {0, 0}, {0, 0, kSide, kSide}, right_kind}};
    }
};

// Mean change (all channels) from column x to column x + 1, rows 8 to kSide - 8.
double column_step(const cv::Mat& rgb, int x) {
    double sum = 0;
    for (int y = 8; y < kSide - 8; ++y)
        for (int c = 0; c < 3; ++c)
            sum += double(rgb.at<cv::Vec3b>(y, x + 1)[c]) - double(rgb.at<cv::Vec3b>(y, x)[c]);
    return sum / (3.0 * (kSide - 16));
}

}  // namespace

TEST_CASE("a tone step between layers of different kinds is spread over their insides",
          "[layer_steps]") {
    const TwoCopies copies(40);
    SteppedCanvas canvas(copies, 1);
    const cv::Mat before = canvas.rgb.clone();
    // The grain's own change across the cut, as either copy shows it.
    const double grain = column_step(copies.dark, kCut - 1);
    REQUIRE(std::abs(column_step(before, kCut - 1) - grain - 40) < 1);
    remove_layer_steps(canvas.rgb, canvas.layer_of, canvas.layers, canvas.fixed);
    INFO("step across the cut " << column_step(canvas.rgb, kCut - 1) << ", the grain's " << grain);
    CHECK(std::abs(column_step(canvas.rgb, kCut - 1) - grain) < 3);
    // The fixed ring is exactly as it was.
    cv::Mat ring_change;
    cv::absdiff(canvas.rgb, before, ring_change);
    ring_change(cv::Rect(1, 1, kSide - 2, kSide - 2)).setTo(0);
    CHECK(cv::countNonZero(ring_change.reshape(1)) == 0);
    // Each side's own detail stays: the change from column to column away from the cut differs
    // from before by no more than the smooth correction's slope.
    for (const int x : {6, 20, 40, 55}) {
        INFO("column " << x);
        CHECK(std::abs(column_step(canvas.rgb, x) - column_step(before, x)) < 3);
    }
    // The step went somewhere smooth: it is not simply moved to the fixed ring's columns.
    CHECK(std::abs(column_step(canvas.rgb, 0) - column_step(before, 0)) < 8);
    CHECK(std::abs(column_step(canvas.rgb, kSide - 2) - column_step(before, kSide - 2)) < 8);
}

TEST_CASE("layers of one kind keep their steps, and a canvas without steps is unchanged",
          "[layer_steps]") {
    const TwoCopies copies(40);
    SteppedCanvas same_kind(copies, 0);
    const cv::Mat before = same_kind.rgb.clone();
    remove_layer_steps(same_kind.rgb, same_kind.layer_of, same_kind.layers, same_kind.fixed);
    CHECK(cv::norm(same_kind.rgb, before, cv::NORM_INF) == 0);

    const TwoCopies equal(0);
    SteppedCanvas no_step(equal, 1);
    const cv::Mat flat = no_step.rgb.clone();
    remove_layer_steps(no_step.rgb, no_step.layer_of, no_step.layers, no_step.fixed);
    CHECK(cv::norm(no_step.rgb, flat, cv::NORM_INF) == 0);
}
