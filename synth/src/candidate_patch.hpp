#pragma once

#include <cstdint>
#include <functional>
#include <opencv2/core/mat.hpp>
#include <optional>

#include "graph_cut.hpp"
#include "lattice_alignment.hpp"
#include "tilejet/synth/internal/diamond.hpp"
#include "tilejet/synth/texture_map.hpp"

namespace tilejet::synth::detail {

struct CandidateSpace {
    // CV_32FC3: the plane around the cell the patches are cut for (the cell image and what its
    // neighbours show), the cell's top-left corner at canvas_origin. The canvas must reach a
    // patch window beyond every side of the cell.
    const cv::Mat& canvas_lab;
    cv::Point canvas_origin;
    const cv::Mat& source_lab;  // CV_32FC3
    CellGrid grid;
    int min_radius = 2;  // patch size r is drawn log-uniformly in [min_radius, max_radius]
    int max_radius = 21;
    // Near-regular exemplars: the source offset q - p is a lattice translation (+-3 px), so a
    // patch brings bricks that line up with the courses around it. Null: any offset.
    const LatticeTranslations* lattice = nullptr;
    // Where, besides the cell's diamond, a patch may reach (cell-relative pixels): only where
    // the canvas is what every cell showing this image has around it. Empty: everywhere.
    std::function<bool(int, int)> exact;
    // How a cut is scored: its largest single edge (false), or its mean edge (true): a seam is
    // seen along its length, and a cut that hugs its forced core where the source disagrees
    // (a square blob) scores badly however small its worst edge.
    bool mean_seam_cost = false;
    // Random source positions drawn per candidate, of which the best match on the ring where
    // the cut runs is cut: 1 for the plain random draw of the Kolář method. A random source
    // disagrees with the plane all around, and its cut hugs the forced core.
    int offset_draws = 1;
    CutLevels cuts = CutLevels::Whole;  // as CellSetParams::cuts
};

// Candidate number `seed` (docs/design.md section 2.4): a random cell position p, source position q
// and size r; in a window of radius 1.5 r around p a min-cut (Boykov-Kolmogorov max-flow)
// separates "take the source" (forced in a core around p) from "keep the cell image" (forced
// on the rim, outside the cell's diamond and where the canvas is not exact). Edge s-t costs
// |cell(s) - src(s)| + |cell(t) - src(t)| in CIELab (Kwatra et al. 2003). seam_cost: see
// mean_seam_cost. Returns nothing when the draw cannot fit (too close to the diamond's edge).
std::optional<Patch> make_candidate(const CandidateSpace& space, uint64_t seed);

// The patch a cut takes over a window of `window` px whose top-left pixel lies at `cell_at` in
// cell coordinates and copies from `source_at`: its mask cropped to what the cut took. Nothing
// when the cut took no pixel.
std::optional<Patch> patch_from_cut(const Cut& cut, cv::Size window, cv::Point cell_at,
                                    cv::Point source_at, float seam_cost);

}  // namespace tilejet::synth::detail
