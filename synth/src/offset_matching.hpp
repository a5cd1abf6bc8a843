#pragma once

// Where in the source a new piece should copy from: like image quilting's block search (Efros
// and Freeman 2001), the offsets whose pixels best match what the plane already shows where the
// piece's seam can run, so that its graph cut finds a good seam. Random offsets made cuts that
// hugged their forced cores: straight-edged blobs, and seams that texture energy counted.

#include <functional>
#include <opencv2/core/mat.hpp>
#include <optional>

#include "lattice_alignment.hpp"
#include "mix64.hpp"

namespace tilejet::synth::detail {

struct OffsetSearch {
    const cv::Mat& source_lab;  // CV_32FC3
    // Offsets allowed besides fitting in the source (a lattice translation, not the piece's
    // own source): `source_corner` is where the window's top-left pixel would copy from.
    std::function<bool(cv::Point source_corner)> allowed;
    double tolerance = 0.1;  // pick at random among offsets within 10% of the best match
    // ... and among at least this many distinct places (the best, each `spread` px or more
    // from the others), however far from the best: with wide overlaps few offsets come within
    // 10%, and pieces that see the same neighbours would all copy the same place.
    int min_choices = 1;
    int spread = 8;
    // Searches a random window of the source this many positions across (0: all of it), as
    // quilting.cpp does on large exemplars: a set quilts over a thousand blocks, and the search
    // over a 512 px source took a 512 px map build past its minute.
    int window = 0;
};

// The source position of `old_lab`'s top-left pixel (CV_32FC3 window of what the plane shows)
// for a new piece: among the positions whose masked squared CIELab difference (mask CV_32F,
// 1 where the seam may run) is within the tolerance of the best, one at random. Nothing when
// no allowed position fits.
std::optional<cv::Point> match_offset(const OffsetSearch& search, const cv::Mat& old_lab,
                                      const cv::Mat& mask, Rng& rng);

}  // namespace tilejet::synth::detail
