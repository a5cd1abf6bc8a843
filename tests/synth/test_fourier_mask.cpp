// Fractional-Fourier masks of exemplars with known lattices.

#include <catch2/catch.hpp>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "fixtures.hpp"
#include "tilejet/synth/fourier_mask.hpp"
#include "tilejet/synth/lattice.hpp"

using namespace tilejet::synth;
using tilejet::test::Basis;

namespace {

// Normalized correlation of `m` with itself moved by `d` (over their overlap).
double shifted_correlation(const cv::Mat& m, cv::Point d) {
    const cv::Rect a(std::max(0, -d.x), std::max(0, -d.y), m.cols - std::abs(d.x),
                     m.rows - std::abs(d.y));
    const cv::Mat x = m(a), y = m(a + d);
    cv::Scalar mx, sx, my, sy;
    cv::meanStdDev(x, mx, sx);
    cv::meanStdDev(y, my, sy);
    cv::Mat xd, yd;
    x.convertTo(xd, CV_64F, 1, -mx[0]);
    y.convertTo(yd, CV_64F, 1, -my[0]);
    return xd.dot(yd) / (double(x.total()) * sx[0] * sy[0]);
}

double distance_to_integer(double v) {
    return std::abs(v - std::round(v));
}

}  // namespace

TEST_CASE("fourier mask: frequencies refined between bins onto the lattice", "[fourier]") {
    // 172 = 7.48 periods of 23 px and 195 = 8.48: the true frequencies fall almost halfway
    // between DFT bins, where the nearest bin is off by 0.48 bin, i.e. f.t by 0.064.
    const Basis truth{{23, 0}, {0, 23}};
    const cv::Mat ex = tilejet::test::make_lattice_texture(truth, {172, 195}, 3, true);
    const FourierMask mask = find_fourier_mask(ex, 6);
    REQUIRE(mask.components.size() == 6);
    for (const FourierComponent& c : mask.components) {
        const double along1 = c.frequency.x * truth.t1.x + c.frequency.y * truth.t1.y;
        const double along2 = c.frequency.x * truth.t2.x + c.frequency.y * truth.t2.y;
        INFO("f (" << c.frequency.x << ", " << c.frequency.y << ") f.t1 " << along1 << " f.t2 "
                   << along2 << " amplitude " << c.amplitude);
        // On the reciprocal lattice: whole cycles per lattice vector, to a fifth of the
        // nearest-bin error.
        CHECK(distance_to_integer(along1) < 0.013);
        CHECK(distance_to_integer(along2) < 0.013);
        CHECK(std::hypot(c.frequency.x, c.frequency.y) > 0.5 / 23);
        CHECK(c.amplitude > 1);
    }
}

TEST_CASE("fourier mask: its peaks repeat at the lattice period, at any size", "[fourier]") {
    const Basis brick{{40, 0}, {20, 17}};
    const cv::Mat ex = tilejet::test::make_lattice_texture(brick, {233, 191}, 6);
    const FourierMask mask = find_fourier_mask(ex);
    const cv::Mat grey = mask.evaluate_8bit(ex.size());
    REQUIRE(grey.size() == ex.size());
    REQUIRE(grey.type() == CV_8U);
    double lo, hi;
    cv::minMaxLoc(grey, &lo, &hi);
    CHECK(lo == 0);
    CHECK(hi == 255);

    // Evaluated past the exemplar (three times its size): still periodic on the lattice, and
    // not at half a brick, so its maxima sit one lattice vector apart.
    const cv::Mat big = mask.evaluate(ex.size() * 3);
    for (cv::Point t : {cv::Point(40, 0), cv::Point(20, 17), cv::Point(-20, 17)}) {
        INFO("shift (" << t.x << ", " << t.y << ")");
        CHECK(shifted_correlation(big, t) > 0.9);
    }
    CHECK(shifted_correlation(big, {20, 0}) < 0.5);
    CHECK(shifted_correlation(big, {0, 8}) < 0.5);

    // The project's own lattice detection sees the brick lattice in the mask.
    cv::Mat rgb;
    cv::cvtColor(grey, rgb, cv::COLOR_GRAY2RGB);
    const Lattice found = detect_lattice(rgb);
    INFO("mask lattice v1 (" << found.v1.x << "," << found.v1.y << ") v2 (" << found.v2.x << ","
                             << found.v2.y << ")");
    CHECK(tilejet::test::same_lattice(found, brick, std::sqrt(2.0)));
}

TEST_CASE("fourier mask: a flat exemplar has no components and a flat mask", "[fourier]") {
    const cv::Mat flat(40, 50, CV_8UC3, cv::Scalar(90, 90, 90));
    const FourierMask mask = find_fourier_mask(flat);
    CHECK(mask.components.empty());
    const cv::Mat grey = mask.evaluate_8bit({50, 40});
    CHECK(cv::countNonZero(grey != 128) == 0);
}
