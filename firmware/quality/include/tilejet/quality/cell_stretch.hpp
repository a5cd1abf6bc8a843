#pragma once

// The stretch of a map's plane that the measures by place in the cell look at: from the origin,
// a cell corner, as many cells each way as fit in a side of so many px, within bounds. One rule
// for all of them, two sizes.

#include <algorithm>
#include <cstdint>
#include <opencv2/core/mat.hpp>

#include "tilejet/synth/texture_map.hpp"

namespace tilejet::quality {

struct CellStretch {
    int most_cells, fewest_cells, most_side;
};

// Texture coherence and the extremes by place (cell_place_energy.hpp, cell_place_tails.hpp):
// 8 x 8 cells or fewer within 2048 px a side, at least 2 x 2.
inline constexpr CellStretch kPlaceStretch{8, 2, 2048};
// The same place of the cell and lines along the cell grid (cell_place_repeat.hpp,
// cell_grid_lines.hpp): 16 x 16 or fewer within 4096 px, at least 4 x 4. Over 8 cells each
// way a plane without lines still measured up to 1.12 along the grid.
inline constexpr CellStretch kWideStretch{16, 4, 4096};

// Cells of `cell_side` px along a side of the stretch.
inline int cells_along(int cell_side, const CellStretch& s) {
    return std::clamp(s.most_side / cell_side, s.fewest_cells, s.most_cells);
}

// The plane of `map` for job `seed` over the stretch, CV_8UC3 R,G,B.
cv::Mat cell_stretch_plane(const synth::TextureMap& map, uint64_t seed, const CellStretch& stretch,
                           int threads = 0);

}  // namespace tilejet::quality
