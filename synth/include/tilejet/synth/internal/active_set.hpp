#pragma once

#include <cstdint>
#include <vector>

#include "tilejet/synth/texture_map.hpp"

namespace tilejet::synth::detail {

// The hash every activation of a cell starts from: (map id, seed, cell image, type, i, j).
uint64_t cell_key(uint64_t map_id, uint64_t seed, uint32_t cell_image, CellType type, int64_t i,
                  int64_t j);

// Activation (docs/design.md section 3.2): fills `active` with the patches k of `set`,
// ascending, for which splitmix64(key + (k + 1) * golden) < activation_threshold.
void activate(const PatchSet& set, uint64_t key, std::vector<uint16_t>& active);

// Overlap removal (section 3.3): while two patches of `active` overlap, drops the one with the
// most overlaps (ties: the lower index).
void remove_overlaps(const PatchSet& set, std::vector<uint16_t>& active);

// The patches shown in the cell whose key is `key`: activate, then remove_overlaps.
inline void compute_active_set(const PatchSet& set, uint64_t key, std::vector<uint16_t>& active) {
    activate(set, key, active);
    remove_overlaps(set, active);
}

}  // namespace tilejet::synth::detail
