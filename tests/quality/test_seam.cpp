#include <catch2/catch.hpp>
#include <opencv2/core.hpp>

#include "../synth/fixtures.hpp"
#include "tilejet/quality/seam.hpp"
#include "walls.hpp"

using namespace tilejet;

namespace {

// One tile whose seam runs down column 99/100 of a 200 px wide image.
quality::Wall split_wall(const cv::Mat& image) {
    quality::Wall w = test::wall_of({image}, 1);
    cv::Mat labels(image.size(), CV_32S, cv::Scalar(1));
    labels.colRange(100, image.cols).setTo(2);
    w.seams = {quality::seams_from_labels(labels)};
    return w;
}

}  // namespace

TEST_CASE("a hard seam raises seam, a seamless cut does not", "[quality]") {
    const cv::Mat& exemplar = test::demo_exemplar();
    const quality::StepStats own = quality::neighbour_steps(exemplar);
    REQUIRE(own.mean > 0);

    // The exemplar itself, "cut" along a column: the step across is an ordinary step.
    const quality::SeamStats invisible =
        quality::measure_seams(split_wall(exemplar(cv::Rect(0, 0, 200, 200)).clone()), own);
    REQUIRE(invisible.known);
    CHECK(invisible.seam.count == 200);
    CHECK(invisible.mean_ratio > 0.5);
    CHECK(invisible.mean_ratio < 1.6);

    // The right half replaced by the exemplar's light-shifted copy: a hard edge at the cut.
    cv::Mat hard = exemplar(cv::Rect(0, 0, 200, 200)).clone();
    cv::Mat right = hard.colRange(100, 200);
    right += cv::Scalar::all(60);
    const quality::SeamStats visible = quality::measure_seams(split_wall(hard), own);
    CHECK(visible.mean_ratio > 2 * invisible.mean_ratio);
    CHECK(visible.p99_ratio > invisible.p99_ratio);
}

TEST_CASE("a wall without known seams reports none", "[quality]") {
    const quality::Wall w = test::wall_of({test::noise_image({32, 32}, 1)}, 1);
    CHECK_FALSE(quality::measure_seams(w, {1, 1, 1}).known);
}
