#pragma once

// Texture coherence (texture_energy.hpp) by place in the cell: along the cell borders and
// inside. A cell set's frame is cut into four strips that come from unrelated places of the
// source, so no one block continues two of them, and its cut runs where nothing matches well;
// on the corpus the band along the borders held most of the coherence tilejet loses to
// quilting (limestone at map seed 1: 2.3 there, 0.8 inside). The gate sees only the mean.

#include <cstddef>
#include <cstdint>
#include <opencv2/core/mat.hpp>

#include "tilejet/quality/cell_stretch.hpp"
#include "tilejet/quality/texture_energy.hpp"
#include "tilejet/synth/texture_map.hpp"

namespace tilejet::quality {

struct CellPlaceEnergy {
    // Mean coherence of 8x8 patches whose centre lies within `band` px of a cell border, and
    // of those further in.
    double border = 0, inside = 0;
    int band = 0;  // px: a tenth of the cell's shorter side, at least 1, as cell_place_repeat
};

// `plane`: CV_8UC3 R,G,B, its top-left pixel a cell corner. `samples` patches of each kind, at
// seeded random places.
CellPlaceEnergy cell_place_energy(const cv::Mat& plane, cv::Size cell, const TextureEnergy& energy,
                                  size_t samples, uint64_t seed);

// The plane of `map` for job `seed` that the measures by place in the cell look at: its
// kPlaceStretch (cell_stretch.hpp), CV_8UC3 R,G,B.
cv::Mat cell_place_plane(const synth::TextureMap& map, uint64_t seed, int threads = 0);

// The same on cell_place_plane().
CellPlaceEnergy cell_place_energy(const synth::TextureMap& map, uint64_t seed,
                                  const TextureEnergy& energy, size_t samples, int threads = 0);

}  // namespace tilejet::quality
