#pragma once

// Where in the source a new piece should copy from: like image quilting's block search (Efros
// and Freeman 2001), the offsets whose pixels best match what the plane already shows where the
// piece's seam can run, so that its graph cut finds a good seam. Random offsets made cuts that
// hugged their forced cores: straight-edged blobs, and seams that texture energy counted.

#include <functional>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "lattice_alignment.hpp"
#include "tilejet/synth/internal/mix64.hpp"

namespace tilejet::synth::detail {

struct OffsetSearch {
    const cv::Mat& source_lab;  // CV_32FC3
    // Offsets allowed besides fitting in the source (a lattice translation, not the piece's
    // own source): `source_corner` is where the window's top-left pixel would copy from.
    std::function<bool(cv::Point source_corner)> allowed;
    // Candidates are this many px or more apart: neighbouring offsets match alike and would
    // offer the caller one place several times.
    int spread = 8;
    // Searches a random window of the source this many positions across (0: all of it), as
    // block_quilting.cpp does on large exemplars: a set quilts over a thousand blocks, and the
    // search over a 512 px source took a 512 px map build past its minute.
    int window = 0;
    // Adds to the match costs of the window positions searched (CV_32F, one per position; the
    // first is the window at `area`'s top-left), or none. Given the area, a caller computes
    // its costs only there: over a slab scan's whole source they took most of a map build.
    std::function<void(const cv::Rect& area, cv::Mat& costs)> add_penalty;
    // The source made `coarse_factor` times smaller (CV_32FC3, coarse_source()), or none.
    // Given, a search that looks at a random window also looks at all of the coarse source
    // and then, at full resolution, round its best places; those join the window's when they
    // match far better (offset_matching.cpp). On an 8192 px slab a random window was 12 px of
    // the photo it was enlarged from, and a block that had to continue a white vein found none
    // there: its cut ran along the window's edge, a straight-sided white shard.
    const cv::Mat* coarse = nullptr;
    int coarse_factor = 1;
};

// Up to `count` allowed source positions of `old_lab`'s top-left pixel (CV_32FC3 window of what
// the plane shows) for a new piece, best first by masked squared CIELab difference (mask
// CV_32F, 1 where the seam may run) plus the penalty, each `spread` px or more from those
// before it. Empty when no allowed position fits.
std::vector<cv::Point> ranked_offsets(const OffsetSearch& search, const cv::Mat& old_lab,
                                      const cv::Mat& mask, Rng& rng, size_t count);

// Whether `search` also looks at its source for a piece of that size coarse to fine: it has a
// coarse source and looks at a random window, and the piece keeps enough pixels made smaller.
bool searches_coarse_to_fine(const OffsetSearch& search, cv::Size piece);

// `image` made `factor` times smaller by area averaging (what is left over at its right and
// bottom edges dropped): OffsetSearch::coarse, and the pieces and masks matched against it.
cv::Mat coarse_source(const cv::Mat& image, int factor);

}  // namespace tilejet::synth::detail
