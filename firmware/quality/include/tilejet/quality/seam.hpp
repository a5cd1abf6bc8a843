#pragma once

// Seams (docs/design.md section 8): where two copied pieces meet, the colour step across the cut
// should look like any step between neighbours inside the exemplar. A visible seam is a step
// larger than the exemplar's own.

#include <opencv2/core/mat.hpp>

#include "tilejet/quality/wall.hpp"

namespace tilejet::quality {

// CIELab steps (Delta E 1976 between 4-neighbours) of an image or of a wall's seams.
struct StepStats {
    double mean = 0, p99 = 0;
    size_t count = 0;
};

// Steps between every pair of horizontal and vertical neighbours of `rgb` (CV_8UC3).
StepStats neighbour_steps(const cv::Mat& rgb);

struct SeamStats {
    bool known = false;     // false when the wall's method records no seams (Wall::seams empty)
    StepStats seam;         // steps across the seams
    double mean_ratio = 0;  // seam.mean / exemplar's mean step
    double p99_ratio = 0;   // seam.p99 / exemplar's 99th percentile step
    double seam_share = 0;  // share of all neighbour pairs that a seam runs between
};

SeamStats measure_seams(const Wall& wall, const StepStats& exemplar, int threads = 0);

}  // namespace tilejet::quality
