#include "lattice_alignment.hpp"

#include <cmath>
#include <cstdlib>

namespace tilejet::synth::detail {

LatticeTranslations::LatticeTranslations(const Lattice& lattice)
    : v1_(lattice.v1), v2_(lattice.v2), det_(double(v1_.x) * v2_.y - double(v1_.y) * v2_.x) {}

cv::Point LatticeTranslations::nearest(cv::Point2d d) const {
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
    return std::abs(p.x - d.x) <= kTolerance && std::abs(p.y - d.y) <= kTolerance;
}

cv::Point LatticeTranslations::near(cv::Point2d target, Rng& rng) const {
    return nearest(target) +
           cv::Point(rng.range(-kTolerance, kTolerance), rng.range(-kTolerance, kTolerance));
}

std::optional<cv::Size> LatticeTranslations::cell_size(int min_side, cv::Size max_size) const {
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
