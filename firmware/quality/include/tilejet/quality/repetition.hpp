#pragma once

// Verbatim repetition on a wall (docs/design.md section 8): what a person notices is not that small
// pieces of the exemplar recur (every copy-based method does that) but that large areas do.
// So repetition is a curve over window size, and a count of tile pairs sharing a large area.

#include <opencv2/core/mat.hpp>
#include <vector>

#include "tilejet/quality/measure_progress.hpp"
#include "tilejet/quality/wall.hpp"

namespace tilejet::quality {

// A window size counts as repeated when repeated windows of that size cover more than this
// share of the wall.
inline constexpr double kRepeatScaleShare = 0.05;

struct RepeatPoint {
    int size = 0;      // S: windows of S x S pixels
    double share = 0;  // share of the wall's pixels covered by S x S windows occurring twice
};

struct Repetition {
    std::vector<RepeatPoint> curve;  // ascending S
    int scale = 0;                   // largest S whose share exceeds kRepeatScaleShare, else 0
    cv::Size shared_window;          // the quarter-tile window tile_pairs_sharing looks for
    double tile_pairs_sharing = 0;   // share of tile pairs holding one identical shared_window
    // Per tile, CV_8U: 0 where no repeated window covers the pixel, else k + 1 where k indexes
    // the largest curve size whose repeated windows cover it. For the heat map.
    std::vector<cv::Mat> heat;
};

// S = 16, 32, 64, 128, 256, those not larger than the tile's shorter side.
std::vector<int> repeat_window_sizes(cv::Size tile);

// Every S x S window of every tile (all positions, not a grid) is hashed with a rolling 2D
// polynomial hash modulo the Mersenne prime 2^61 - 1; windows whose hashes are equal count as
// identical without a byte comparison. For two different windows the chance of equal hashes
// is below 2S / 2^61 (Schwartz-Zippel), so on a wall of 5e7 windows false matches are expected
// on well under one window per size. Windows never straddle tile joints: neighbouring tiles of
// a canvas or of quilting are not neighbours in what they copy.
// Memory: about 13 bytes per pixel of the wall at the smallest S.
Repetition measure_repetition(const Wall& wall, int threads = 0,
                              const MeasureProgress& progress = {});

}  // namespace tilejet::quality
