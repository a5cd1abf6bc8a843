#pragma once

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <optional>

#include "diamond.hpp"
#include "lattice_alignment.hpp"
#include "tilejet/synth/texture_map.hpp"

namespace tilejet::synth::detail {

struct CandidateSpace {
    const cv::Mat& cell_lab;    // CV_32FC3, wraps around
    const cv::Mat& source_lab;  // CV_32FC3
    CellGrid grid;
    int min_radius = 2;  // patch size r is drawn log-uniformly in [min_radius, max_radius]
    int max_radius = 21;
    // Near-regular exemplars: the source offset q - p is a lattice translation (+-3 px), so a
    // patch brings bricks that line up with the courses around it. Null: any offset.
    const LatticeTranslations* lattice = nullptr;
};

// Candidate number `seed` (design.md section 2.4): a random cell position p, source position q
// and size r; in a window of radius 1.5 r around p a min-cut (Boykov-Kolmogorov max-flow)
// separates "take the source" (forced in a core around p) from "keep the cell image" (forced
// on the rim and outside the cell's diamond). Edge s-t costs |cell(s) - src(s)| +
// |cell(t) - src(t)| in CIELab (Kwatra et al. 2003). seam_cost is the largest edge on the cut.
// Returns nothing when the draw cannot fit (too close to the diamond's edge).
std::optional<Patch> make_candidate(const CandidateSpace& space, uint64_t seed);

}  // namespace tilejet::synth::detail
