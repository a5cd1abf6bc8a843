// The min-cut between two images of one window, exact and coarse to fine.

#include <catch2/catch.hpp>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <random>

#include "graph_cut.hpp"

using namespace tilejet::synth::detail;

namespace {

// A soft random CIELab image, as an enlarged exemplar is: noise blurred over `blur` px.
cv::Mat soft_lab(cv::Size size, double blur, std::uint32_t seed) {
    cv::Mat noise(size, CV_32FC3);
    cv::RNG rng(seed);
    rng.fill(noise, cv::RNG::NORMAL, cv::Scalar::all(0), cv::Scalar::all(40));
    cv::GaussianBlur(noise, noise, {0, 0}, blur);
    return noise;
}

// A patch window's pins: the new image forced in a centred core, the old one on the rim.
std::vector<Pin> core_and_rim(cv::Size size, int core) {
    std::vector<Pin> pins(size.area(), Pin::Free);
    for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x) {
            const bool rim = x == 0 || y == 0 || x == size.width - 1 || y == size.height - 1;
            if (rim)
                pins[size_t(y * size.width + x)] = Pin::Old;
            else if (std::abs(x - size.width / 2) <= core && std::abs(y - size.height / 2) <= core)
                pins[size_t(y * size.width + x)] = Pin::New;
        }
    return pins;
}

void check_pins_kept(const Cut& cut, const std::vector<Pin>& pins) {
    size_t broken = 0;
    for (size_t n = 0; n < pins.size(); ++n)
        broken +=
            (pins[n] == Pin::New && !cut.take_new[n]) || (pins[n] == Pin::Old && cut.take_new[n]);
    CHECK(broken == 0);
}

}  // namespace

TEST_CASE("a large window's coarse-to-fine cut keeps every pin", "[graph_cut]") {
    const cv::Size size(kBandedCutSide * 3 + 1, kBandedCutSide * 2 + 3);  // odd sides
    const auto pins = core_and_rim(size, 30);
    const Cut cut = min_cut(soft_lab(size, 4, 1), soft_lab(size, 4, 2), pins, CutLevels::Auto);
    check_pins_kept(cut, pins);
    CHECK(cut.taken > 61 * 61);
    CHECK(cut.taken < size_t(size.area()));
}

// The cut must find a narrow valley, which the half-resolution pass only sees blurred.
TEST_CASE("the coarse-to-fine cut follows a two-pixel valley where the images agree",
          "[graph_cut]") {
    static_assert(301 >= kBandedCutSide);
    const cv::Size size(301, 301);
    cv::Mat old_lab(size, CV_32FC3, cv::Scalar(50, 0, 0)), new_lab = old_lab.clone();
    new_lab.setTo(cv::Scalar(80, 20, -20));
    // Agreement on a ring 2 px wide around the centre, off the half-resolution grid's phase.
    for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x) {
            const double r = std::hypot(x - 150.5, y - 149.7);
            if (r >= 91.3 && r < 93.3) new_lab.at<cv::Vec3f>(y, x) = old_lab.at<cv::Vec3f>(y, x);
        }
    const auto pins = core_and_rim(size, 40);
    const Cut exact = min_cut(old_lab, new_lab, pins, CutLevels::Whole);
    const Cut banded = min_cut(old_lab, new_lab, pins, CutLevels::Auto);
    check_pins_kept(banded, pins);
    // Along the valley an edge costs only the floor; anywhere else it costs twice the distance.
    CHECK(exact.max_cost < 1e-2f);
    CHECK(banded.max_cost < 1e-2f);
    // Equal up to where the pixelated ring leaves the cut a choice of equal cost.
    CHECK(banded.total_cost <= exact.total_cost * 1.02);
    CHECK(std::abs(double(banded.taken) - double(exact.taken)) < 2 * M_PI * 92);
}

// Max-flow's cut is the minimum, so the banded one can only cost more: by little, on the
// soft windows (enlarged exemplars) whose patches are large enough to be cut coarse to fine.
TEST_CASE("the coarse-to-fine cut costs close to the exact minimum", "[graph_cut]") {
    for (std::uint32_t seed = 1; seed <= 6; ++seed) {
        const cv::Size size(kBandedCutSide + int(seed) * 17, kBandedCutSide + int(seed) * 13);
        const double blur = 1.5 + seed;
        const auto pins = core_and_rim(size, 35);
        const cv::Mat old_lab = soft_lab(size, blur, 10 + seed),
                      new_lab = soft_lab(size, blur, 20 + seed);
        const Cut exact = min_cut(old_lab, new_lab, pins, CutLevels::Whole);
        const Cut banded = min_cut(old_lab, new_lab, pins, CutLevels::Auto);
        INFO("seed " << seed << ": exact " << exact.total_cost << ", banded " << banded.total_cost);
        CHECK(banded.total_cost >= exact.total_cost * (1 - 1e-6));
        CHECK(banded.total_cost <= exact.total_cost * 1.10);
    }
}

TEST_CASE("a small window is cut exactly", "[graph_cut]") {
    const cv::Size size(kBandedCutSide - 1, kBandedCutSide + 40);
    const auto pins = core_and_rim(size, 12);
    const cv::Mat old_lab = soft_lab(size, 2, 5), new_lab = soft_lab(size, 2, 6);
    const Cut exact = min_cut(old_lab, new_lab, pins, CutLevels::Whole);
    const Cut cut = min_cut(old_lab, new_lab, pins, CutLevels::Auto);
    CHECK(cut.take_new == exact.take_new);
}

// Two cuts of the same mean cost: one along a uniform difference, one whose cost lies all in a
// quarter of its length (a vein cut off square). The squared mean tells them apart, by the
// factor the construction gives: costs 20 everywhere against 80 on a quarter, 0 elsewhere.
TEST_CASE("a cut's mean squared cost weighs a short costly stretch more than its mean does",
          "[graph_cut]") {
    const cv::Size size(16, 64);
    // Every pixel pinned: the cut runs between columns 7 and 8, 64 edges.
    std::vector<Pin> pins(size_t(size.area()));
    for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x)
            pins[size_t(y * size.width + x)] = x < size.width / 2 ? Pin::Old : Pin::New;
    const cv::Mat old_lab(size, CV_32FC3, cv::Scalar(50, 0, 0));
    // Each edge costs the difference at both its pixels: 10 + 10, or 40 + 40 over a quarter.
    const cv::Mat uniform(size, CV_32FC3, cv::Scalar(60, 0, 0));
    cv::Mat stretch = old_lab.clone();
    stretch.rowRange(0, size.height / 4).setTo(cv::Scalar(90, 0, 0));
    const Cut even = min_cut(old_lab, uniform, pins, CutLevels::Whole);
    const Cut square = min_cut(old_lab, stretch, pins, CutLevels::Whole);
    CHECK(even.mean_cost == Approx(20).epsilon(1e-3));
    CHECK(square.mean_cost == Approx(20).epsilon(1e-3));
    CHECK(even.mean_square_cost == Approx(400).epsilon(1e-3));
    CHECK(square.mean_square_cost == Approx(0.25 * 80 * 80).epsilon(1e-3));
}
