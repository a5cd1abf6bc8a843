#pragma once

// Frame patches: patches that carry a cell's frame strip on into the cell (design §9).
//
// Every cell image shows, along each edge, its half of a strip that its neighbour across the
// edge shows too, and its own blocks cut into that strip within a tenth of the cell of the
// border. All those cuts lie in the same thin band of every cell: the plane shows its cells as
// squares (session 33's diagnosis, the lines gate). A strip is one window of the source, so the
// source beyond that window continues it exactly. A frame patch copies that continuation, from
// the border to a cut well inside the cell: along the strip it shows what the cell shows there
// already (no seam), and it hides the cell's own cut into the strip under its own, which the
// max-flow places anywhere between its forced core and its window's inner edge. Shown by hash
// cell by cell like any patch, the cut along each edge of a cell lies at a different depth in
// different cells, and the band along the borders is no longer one line.

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <optional>

#include "graph_cut.hpp"
#include "tilejet/synth/texture_map.hpp"

namespace tilejet::synth::detail {

enum class CellEdge : uint8_t { top, bottom, left, right };

struct ContinuationSpace {
    const cv::Mat& image_lab;   // CV_32FC3: the cell image the patch is cut against
    const cv::Mat& source_lab;  // CV_32FC3: the map's source
    CellEdge edge;
    // Image pixel p of the edge's strip shows source pixel p + offset (CellSet::strip_offset()).
    cv::Point offset;
    int frame = 0;  // the strip's half-width inside the cell (CellSet: w)
    CutLevels cuts = CutLevels::Whole;
};

// Candidate number `seed`: a stretch of the edge away from its corners, a depth into the cell
// between the frame and a quarter of the cell, a core forced to the continuation just
// inside the frame, the window's rim kept as the image shows it. Nothing when the continuation
// runs out of the source, or where the cell shows it already. The patch lies inside the cell;
// its seam_cost is its cut's mean edge cost.
std::optional<Patch> make_continuation(const ContinuationSpace& space, uint64_t seed);

}  // namespace tilejet::synth::detail
