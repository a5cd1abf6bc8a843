#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "tilejet/synth/internal/mix64.hpp"

namespace tilejet::synth::detail {

struct BicliqueSplit {
    std::vector<size_t> a, b;  // ascending
};

// Splits patches 0..n-1 into sets A and B such that no member of A conflicts with any member
// of B (docs/design.md section 2.6). `conflict` is an n x n symmetric matrix, row-major. Greedy:
// seed with a non-conflicting pair, then alternately add to A a random patch that conflicts with
// nothing in B and to B one that conflicts with nothing in A, until every patch is placed or none
// fits either side.
BicliqueSplit split_pseudo_biclique(size_t n, const std::vector<uint8_t>& conflict, Rng& rng);

}  // namespace tilejet::synth::detail
