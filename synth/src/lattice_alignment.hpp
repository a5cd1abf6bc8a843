#pragma once

#include <opencv2/core/types.hpp>
#include <optional>

#include "tilejet/synth/internal/mix64.hpp"
#include "tilejet/synth/lattice.hpp"

namespace tilejet::synth::detail {

// Translations that keep a near-regular texture's structure: the lattice's points, give or take
// a few pixels (docs/design.md section 7: offsets restricted to lattice translations within
// +-3 px). For courses: any distance along them, whole pitches across them, give or take a
// twelfth of the pitch (a brick wall's mortar is a pixel or two thick on a 17 px pitch: 3 px
// broke it).
class LatticeTranslations {
  public:
    static constexpr int kTolerance = 3;  // px
    explicit LatticeTranslations(const Lattice& lattice);

    cv::Point nearest(cv::Point2d d) const;  // the lattice point closest to d
    bool allows(cv::Point d) const;          // d within tolerance of a lattice point (each axis)
    // A random allowed translation near `target`.
    cv::Point near(cv::Point2d target, Rng& rng) const;

    // The smallest cell rectangle (Cx, Cy) whose sides are lattice vectors (or within 1 px of
    // one, for lattices with no exact axis-aligned vectors), grown by whole multiples to at least
    // `min_side`; nothing when it cannot fit in `max_size`.
    std::optional<cv::Size> cell_size(int min_side, cv::Size max_size) const;

  private:
    cv::Point v1_, v2_;
    double det_;
    double pitch_ = 0;  // courses only: the exact pitch along v2
    int tolerance_ = kTolerance;
};

}  // namespace tilejet::synth::detail
