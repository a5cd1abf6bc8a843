#pragma once

// Lattices of near-regular exemplars (docs/design.md section 7): brick, mosaics, tiled floors and
// textiles repeat along two translation vectors v1, v2 (the lattice), with variation. Laid
// brick and setts often repeat one way only: courses at a steady pitch, whose joints fall
// anywhere along them (bricks and stones of varying length).

#include <array>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string_view>

namespace tilejet::synth {

enum class LatticeKind { Regular, NearRegular, Courses, Stochastic };
std::string_view lattice_kind_name(LatticeKind kind);

struct Lattice {
    cv::Point v1{1, 0}, v2{0, 1};  // integer pixel vectors; (1,0), (0,1) when stochastic
    double score = 0;              // mean^alpha * n^(alpha-1) of the chosen pair (0: none)
    LatticeKind kind = LatticeKind::Stochastic;
    // Regularity when a lattice exists: G (geometry) is the mean normalized correlation of the
    // exemplar with itself shifted by the lattice's vectors; A (appearance) is how alike the
    // lattice's tiles look, 1 minus their variance about the mean tile relative to the image's.
    std::optional<double> geometry_regularity, appearance_regularity;
    // Courses: v1 is the unit vector along them ((1,0) or (0,1)), v2 the pitch rounded to whole
    // pixels across them, `pitch` the pitch itself (a fraction of a pixel adds up over courses).
    double pitch = 0;
    int area() const { return std::abs(v1.x * v2.y - v1.y * v2.x); }
};

// Detects the lattice of `rgb` (CV_8UC3) by the generalized normalized cross-correlation of
// the image with itself over every overlap (FFT for the cross term, summed-area tables for the
// means and energies, channels weighted by their energy), then scores pairs of its peaks.
Lattice detect_lattice(const cv::Mat& rgb);

}  // namespace tilejet::synth
