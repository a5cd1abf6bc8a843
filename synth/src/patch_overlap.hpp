#pragma once

#include "tilejet/synth/texture_map.hpp"

namespace tilejet::synth::detail {

// Whether patch `b`, shown in a cell displaced by (dx, dy) pixels from `a`'s cell, covers any
// pixel that `a` covers.
bool patches_overlap(const Patch& a, const Patch& b, int dx, int dy);

}  // namespace tilejet::synth::detail
