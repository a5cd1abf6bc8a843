#pragma once

// How much of the plane the shown patches cover (issue 16, point 2). Whatever no patch covers
// shows a cell image, and a cell image repeats on the lattice: the uncovered share is the part
// of the wall that can look like a grid, so the quality report and `map info` state it.

#include <cstdint>

#include "tilejet/synth/sampler.hpp"
#include "tilejet/synth/texture_map.hpp"

namespace tilejet::quality {

// The share in [0, 1] of `region`'s pixels that show a patch rather than a cell image: exactly
// the pixels render_patch_labels labels non-zero. Throws SynthError for an empty region (no
// share to speak of) or one outside the plane.
double patch_coverage(const synth::TextureMap& map, uint64_t seed, const synth::Region& region);

}  // namespace tilejet::quality
