// The tone step a cut leaves: the source's tone, a canvas's known tone, the step across a cut.

#include <catch2/catch.hpp>
#include <cmath>

#include "seam_tone.hpp"

using namespace tilejet::synth::detail;

namespace {

// A CIELab image of lightness `left` left of column `edge` and `right` from it on.
cv::Mat two_tones(cv::Size size, int edge, float left, float right) {
    cv::Mat lab(size, CV_32FC3, cv::Scalar(left, 5, -5));
    lab(cv::Rect(edge, 0, size.width - edge, size.height)).setTo(cv::Scalar(right, 5, -5));
    return lab;
}

// A cut of a `size` window that takes the new image from column `from` on.
Cut new_from_column(cv::Size size, int from) {
    Cut cut;
    cut.take_new.assign(size_t(size.area()), 0);
    for (int y = 0; y < size.height; ++y)
        for (int x = from; x < size.width; ++x)
            cut.take_new[size_t(y * size.width + x)] = 1;
    return cut;
}

}  // namespace

TEST_CASE("a source's tone is its colour blurred, kept every half blur", "[seam_tone]") {
    const cv::Mat lab = two_tones({400, 300}, 200, 40, 60);
    const SourceTone tone(lab, 16);
    CHECK(tone.step() == 8);
    CHECK(tone.sigma() == 16);
    // Far from the edge, the tone is the colour; at the edge, between the two.
    CHECK(tone.at({10, 150})[0] == Approx(40).margin(0.01));
    CHECK(tone.at({390, 150})[0] == Approx(60).margin(0.01));
    CHECK(tone.at({399, 299})[0] == Approx(60).margin(0.01));  // the last, partly kept sample
    const float at_edge = tone.at({200, 150})[0];
    CHECK(at_edge > 45);
    CHECK(at_edge < 55);
    CHECK(tone.at({200, 150})[1] == Approx(5).margin(0.01));
    // A blur under 2 px is kept at every pixel.
    CHECK(SourceTone(lab, 1.5).step() == 1);
}

TEST_CASE("a canvas's tone leaves out what it does not show yet", "[seam_tone]") {
    // Known: lightness 50 left of column 30; unknown (zeros) from it on.
    const cv::Size size(80, 40);
    const cv::Mat lab = two_tones(size, 30, 50, 0);
    cv::Mat known(size, CV_8U, cv::Scalar(0));
    known(cv::Rect(0, 0, 30, 40)).setTo(255);
    const cv::Mat tone = known_tone(lab, known, cv::Rect(20, 10, 20, 20), 4);
    REQUIRE(tone.size() == cv::Size(20, 20));
    REQUIRE(tone.type() == CV_32FC3);
    // Next to the unknown pixels and a few px into them, the tone is the known one's.
    CHECK(tone.at<cv::Vec3f>(5, 9)[0] == Approx(50).margin(0.01));
    CHECK(tone.at<cv::Vec3f>(5, 12)[0] == Approx(50).margin(0.01));
    // All known: an ordinary blur.
    const cv::Mat all =
        known_tone(two_tones(size, 40, 40, 60), cv::Mat(size, CV_8U, cv::Scalar(255)),
                   cv::Rect(0, 0, 80, 40), 4);
    CHECK(all.at<cv::Vec3f>(20, 5)[0] == Approx(40).margin(0.01));
    CHECK(all.at<cv::Vec3f>(20, 75)[0] == Approx(60).margin(0.01));
}

TEST_CASE("the tone step across a cut is the tone difference along its new side", "[seam_tone]") {
    const cv::Size window(60, 40);
    const cv::Mat old_tone(window, CV_32FC3, cv::Scalar(50, 5, -5));
    const Cut cut = new_from_column(window, 30);
    // A source whose tone at the copied window is 56 (columns 100 on): a step of 6.
    const SourceTone lighter(two_tones({300, 100}, 100, 50, 56), 1);
    CHECK(seam_tone_step(cut, old_tone, lighter, {120, 20}) == Approx(6).margin(1e-4));
    // The same tone on both sides: no step.
    CHECK(seam_tone_step(cut, old_tone, lighter, {10, 20}) == Approx(0).margin(1e-4));
    // Only the new side's pixels next to the old side count: a copy lighter beyond the seam's
    // column alone (source columns from 160 on, window columns from 40 on) leaves no step.
    const SourceTone lighter_inside(two_tones({300, 100}, 160, 50, 70), 1);
    CHECK(seam_tone_step(cut, old_tone, lighter_inside, {120, 20}) == Approx(0).margin(1e-4));
    // A cut that keeps all old or takes all new leaves no seam.
    CHECK(seam_tone_step(new_from_column(window, 60), old_tone, lighter, {120, 20}) == 0);
    CHECK(seam_tone_step(new_from_column(window, 0), old_tone, lighter, {120, 20}) == 0);
}
