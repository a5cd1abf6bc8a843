#include "lattice_alignment.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace tilejet::synth::detail {

LatticeTranslations::LatticeTranslations(const Lattice& lattice)
    : v1_(lattice.v1), v2_(lattice.v2), det_(double(v1_.x) * v2_.y - double(v1_.y) * v2_.x) {
    if (lattice.kind == LatticeKind::Courses) {
        pitch_ = lattice.pitch;
        tolerance_ = std::clamp(int(std::lround(pitch_ / 12)), 1, kTolerance);
    }
}

cv::Point LatticeTranslations::nearest(cv::Point2d d) const {
    if (pitch_ > 0) {
        // Along the courses as it is; across, the nearest whole number of pitches.
        const bool rows = v1_.x != 0;  // courses run along x, pitched along y
        const double a = rows ? d.y : d.x, b = rows ? d.x : d.y;
        const int snapped = int(std::lround(std::round(a / pitch_) * pitch_));
        const int along = int(std::lround(b));
        return rows ? cv::Point(along, snapped) : cv::Point(snapped, along);
    }
    // Lattice coordinates of d, rounded, then the best of the four surrounding points (the
    // rounded coordinates alone can miss on a strongly sheared basis).
    const double u = (d.x * v2_.y - d.y * v2_.x) / det_, v = (d.y * v1_.x - d.x * v1_.y) / det_;
    cv::Point best;
    double best_d2 = -1;
    for (int du = 0; du <= 1; ++du)
        for (int dv = 0; dv <= 1; ++dv) {
            const int a = int(std::floor(u)) + du, b = int(std::floor(v)) + dv;
            const cv::Point p(a * v1_.x + b * v2_.x, a * v1_.y + b * v2_.y);
            const double d2 = (p.x - d.x) * (p.x - d.x) + (p.y - d.y) * (p.y - d.y);
            if (best_d2 < 0 || d2 < best_d2) best = p, best_d2 = d2;
        }
    return best;
}

bool LatticeTranslations::allows(cv::Point d) const {
    const cv::Point p = nearest(d);
    return std::abs(p.x - d.x) <= tolerance_ && std::abs(p.y - d.y) <= tolerance_;
}

cv::Point LatticeTranslations::near(cv::Point2d target, Rng& rng) const {
    return nearest(target) +
           cv::Point(rng.range(-tolerance_, tolerance_), rng.range(-tolerance_, tolerance_));
}

std::optional<cv::Size> LatticeTranslations::cell_size(int min_side, cv::Size max_size) const {
    if (pitch_ > 0) {
        // Along the courses any length; across, the whole number of pitches (at least
        // min_side) that lands nearest a whole pixel, of the first few: cells restart the
        // courses' phase, and what the rounding leaves shows as a step at every cell border.
        const bool rows = v1_.x != 0;
        const int along = std::min(min_side, rows ? max_size.width : max_size.height);
        const int room = rows ? max_size.height : max_size.width;
        const int first = std::max(1, int(std::ceil(min_side / pitch_)));
        int best = 0;
        double best_error = 1e9;
        for (int m = first; m < first + 4; ++m) {
            const int side = int(std::lround(m * pitch_));
            const double error = std::abs(side - m * pitch_);
            if (side <= room && error < best_error - 1e-9) best = side, best_error = error;
        }
        if (best == 0 || along < 1) return std::nullopt;
        return rows ? cv::Size(along, best) : cv::Size(best, along);
    }
    // Shortest lattice vectors that are horizontal (vertical) to within a pixel.
    constexpr int kSearch = 24;
    int best_x = 0, best_y = 0;
    for (int a = -kSearch; a <= kSearch; ++a)
        for (int b = -kSearch; b <= kSearch; ++b) {
            const int x = a * v1_.x + b * v2_.x, y = a * v1_.y + b * v2_.y;
            if (std::abs(y) <= 1 && std::abs(x) > 1 && (best_x == 0 || std::abs(x) < best_x))
                best_x = std::abs(x);
            if (std::abs(x) <= 1 && std::abs(y) > 1 && (best_y == 0 || std::abs(y) < best_y))
                best_y = std::abs(y);
        }
    if (best_x == 0 || best_y == 0) return std::nullopt;
    auto side = [&](int period, int max) -> int {
        const int wanted = (min_side + period - 1) / period, fits = max / period;
        return fits < 1 ? 0 : period * std::min(std::max(1, wanted), fits);
    };
    const int cx = side(best_x, max_size.width), cy = side(best_y, max_size.height);
    if (cx == 0 || cy == 0) return std::nullopt;
    return cv::Size(cx, cy);
}

}  // namespace tilejet::synth::detail
