#pragma once

// Which cell image a cell shows (docs/design.md section 9). Every lattice vertex (i, j), the
// top-left corner of cell (i, j), gets one of K colours by integer hash of (map, seed, i, j); a
// cell shows the image made for its four corners' colours (of the variant of its parity, when a
// set has two). Neighbouring cells share two corners, and the images of a set are built so that
// any two that share corner colours meet seamlessly (cell_set.hpp), so whatever the hash picks
// is seamless, and neither a cell image nor an edge nor a corner lies on a grid.

#include <cstdint>

#include "tilejet/synth/internal/mix64.hpp"
#include "tilejet/synth/texture_map.hpp"

namespace tilejet::synth::detail {

class CornerColours {
  public:
    CornerColours(const TextureMap& map, uint64_t seed)
        : k_(uint64_t(map.corner_colours)),
          variants_(map.variants),
          key_(hash_combine(hash_combine(map.id64(), seed), kVertexStream)) {}

    // Uniform in [0, K) by Lemire's multiply-shift: no division, bias below 2^-60 for small K.
    uint32_t colour(int64_t i, int64_t j) const {
        if (k_ == 1) return 0;
        const uint64_t h = hash_combine(hash_combine(key_, uint64_t(i)), uint64_t(j));
        return uint32_t(uint128(h) * k_ >> 64);
    }

    // The cell image index of cell (i, j): tl + K tr + K^2 bl + K^3 br, plus K^4 for the second
    // variant on cells of odd i + j. A checkerboard of variants rather than a hashed one: the
    // four cells across an edge from a cell always show the other variant, so never its image.
    // The two variants are made alike (cell_set.hpp), so the checkerboard itself does not show.
    uint32_t image(int64_t i, int64_t j) const {
        if (k_ == 1) return 0;
        const uint32_t combination =
            image_of(colour(i, j), colour(i + 1, j), colour(i, j + 1), colour(i + 1, j + 1));
        if (variants_ == 1) return combination;
        return combination + uint32_t(k_ * k_ * k_ * k_) * uint32_t((i + j) & 1);
    }
    uint32_t image_of(uint32_t tl, uint32_t tr, uint32_t bl, uint32_t br) const {
        return uint32_t(tl + k_ * (tr + k_ * (bl + k_ * br)));
    }

  private:
    // Keeps vertex colours independent of the activation hashes of the same map and seed.
    static constexpr uint64_t kVertexStream = 0x636f726e6572ull;  // "corner"
    uint64_t k_;
    int variants_;
    uint64_t key_;
};

}  // namespace tilejet::synth::detail
