#pragma once

// Block quilting (Efros and Freeman 2001), the engine under every quilted image but the cell
// sets': blocks found by an FFT block search, joined along minimum-cost paths, over a canvas that
// wraps (a one-image map's cell image, an exemplar's enlargement) or not (quilt.hpp's images).

#include <opencv2/core/mat.hpp>

#include "lattice_alignment.hpp"
#include "tilejet/synth/internal/mix64.hpp"

namespace tilejet::synth::detail {

struct QuiltParams {
    int block = 32;          // square block side b
    int overlap = 5;         // overlap o between neighbouring blocks
    double tolerance = 0.1;  // candidates within 10% of the best overlap error are eligible
    // Near-regular exemplars: blocks only from positions a lattice translation (+-3 px) away
    // from where they go, so bricks stay in their courses. Null: anywhere.
    const LatticeTranslations* lattice = nullptr;
};

// Image quilting (Efros and Freeman 2001) on a torus: blocks are laid in raster order over a
// grid that wraps, so the last column and row are matched against the first and the result
// tiles seamlessly. Overlaps are cut along minimum-error boundary paths (dynamic programming).
// `exemplar_lab` is to_lab(exemplar_rgb); returns CV_8UC3 R,G,B of `size`.
cv::Mat quilt_toroidal(const cv::Mat& exemplar_rgb, const cv::Mat& exemplar_lab, cv::Size size,
                       const QuiltParams& params, Rng& rng);

// The same quilting on a plain rectangle: nothing wraps, so the left column and top row of
// blocks match nothing and the result need not tile (the image quilting of the paper, for
// outputs larger than any cell).
cv::Mat quilt_open(const cv::Mat& exemplar_rgb, const cv::Mat& exemplar_lab, cv::Size size,
                   const QuiltParams& params, Rng& rng);

}  // namespace tilejet::synth::detail
