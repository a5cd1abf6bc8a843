#pragma once

// Where a wall keeps its extremes, by place in the cell: the share of the plane in its own
// lightest 5 % (veins, flecks) and in its darkest 5 % (pits, cracks), along the cell borders and
// inside the cells. A cell set's frame strips are shared by every cell with their corner
// colours, and blocks that join a calm strip choose calm windows: where frames are calmer than
// the rest, the wall shows calm lines along the cell rows and columns, a grid that periodicity
// and texture energy hardly see (the demo design at 100 dpi: 3.8 % of the border band in the
// lightest 5 % against 5.7 % inside; session 31). On a wall without a grid both are about 5 %.
// The plane's own extremes, not the exemplar's: how many of those a wall keeps is colour's
// light and dark tail (colour_match.hpp), where they lie is this.

#include <cstdint>
#include <opencv2/core/mat.hpp>

#include "tilejet/quality/colour_match.hpp"
#include "tilejet/synth/texture_map.hpp"

namespace tilejet::quality {

struct CellPlaceTails {
    // Shares of the pixels within `band` px of a cell border, and of those further in, lighter
    // than the lightest kTailShare / darker than the darkest.
    double border_light = 0, inside_light = 0, border_dark = 0, inside_dark = 0;
    int band = 0;  // px: a tenth of the cell's shorter side, at least 1, as cell_place_repeat
};

// `plane`: CV_8UC3 R,G,B, its top-left pixel a cell corner; `light` and `dark`: the L* above
// which, and below which, a pixel counts as one of the extremes.
CellPlaceTails cell_place_tails(const cv::Mat& plane, cv::Size cell, double light, double dark);

// Against the plane's own lightest and darkest kTailShare (a map's: cell_place_plane(),
// cell_place_energy.hpp).
CellPlaceTails cell_place_tails(const cv::Mat& plane, cv::Size cell);

}  // namespace tilejet::quality
