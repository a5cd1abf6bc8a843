#pragma once

// Constrained random sampling with gap filling (docs/design.md section 7): a near-regular texture
// enlarged block by block so that every copy stays on the exemplar's lattice.

#include <cstdint>
#include <opencv2/core/mat.hpp>

#include "tilejet/synth/lattice.hpp"

namespace tilejet::synth {

// Synthesizes `size` from `exemplar` (CV_8UC3 R,G,B) on `lattice` (detect_lattice's result):
// the output is cut into a chessboard of lattice-compatible blocks; the "black" ones are copied
// from random exemplar positions a whole lattice translation away, the "white" gaps from the
// position within +-3 px of a lattice translation whose border matches the blocks around it
// best, and a short linear blend runs across every gap's border. A stochastic lattice ((1,0),
// (0,1)) constrains nothing: it degrades to random blocks with matched gaps.
cv::Mat synthesize_rsgf(const cv::Mat& exemplar, const Lattice& lattice, cv::Size size,
                        uint64_t seed);

}  // namespace tilejet::synth
