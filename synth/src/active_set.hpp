#pragma once

#include <cstdint>
#include <vector>

#include "tilejet/synth/texture_map.hpp"

namespace tilejet::synth::detail {

// The hash every activation of a cell starts from: (map id, seed, cell image, type, i, j).
uint64_t cell_key(uint64_t map_id, uint64_t seed, uint32_t cell_image, CellType type, int64_t i,
                  int64_t j);

// Fills `active` with the patches of `set` shown in the cell whose key is `key`, ascending:
// patch k is active when splitmix64(key + (k + 1) * golden) < activation_threshold, then while
// two active patches overlap, the one with most overlaps is dropped (ties: the lower index).
void compute_active_set(const PatchSet& set, uint64_t key, std::vector<uint16_t>& active);

}  // namespace tilejet::synth::detail
