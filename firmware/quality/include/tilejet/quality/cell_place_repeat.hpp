#pragma once

// How often the plane shows the same thing at the same place of the cell (issue 16): the grid
// a wall folded by the cell size shows. One cell image repeats everywhere no patch covers it;
// a corner-coloured set varies its images, but the strips along the cell borders are shared by
// every edge of their kind, one edge in K^2, and the band round the borders repeats on the grid
// while the insides do not. Periodicity sees that only as part of one autocorrelation peak.

#include <cstdint>

#include "tilejet/synth/texture_map.hpp"

namespace tilejet::quality {

struct CellPlaceRepeat {
    // Per place of the cell, the share of cells showing its most common pixel there, averaged
    // over the band within `band` px of the cell's border and over the places inside it.
    double border = 0, inside = 0;
    // px: a tenth of the cell's shorter side, at least 1: a cell set's frame (which is at
    // least 3 px) for cells of 30 px and more.
    int band = 0;
    int cells = 0;  // cells compared
};

// Samples the cells of the plane from the origin for job `seed`, 16 x 16 of them or fewer, so
// that they stay within 4096 px a side (at least 4 x 4 cells), and folds them: every place of
// cells up to 256 px, places a few px apart in larger ones (up to 256 a side).
CellPlaceRepeat cell_place_repeat(const synth::TextureMap& map, uint64_t seed);

}  // namespace tilejet::quality
