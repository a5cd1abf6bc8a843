#pragma once

// Which cell image a cell shows (docs/design.md section 9). Every lattice vertex (i, j), the
// top-left corner of cell (i, j), gets one of K colours by integer hash of (map, seed, i, j); a
// cell shows the image made for its four corners' colours (in a set of two variants, the
// variant its rule picks). Neighbouring cells share two corners, and the images of a set are built
// so that any two that share corner colours meet seamlessly (cell_set.hpp), so whatever the hash
// picks is seamless, and neither a cell image nor an edge nor a corner lies on a grid.
//
// With K = 2 two neighbours show one combination one time in 16 across an edge and across a
// vertex alike, and a cell has eight neighbours: on a wall about two cells in five touched a
// copy of themselves, the motif doubled that the eye and `tilejet eval`'s periodicity find
// first. Sets of two variants break those twins (TextureMap::VariantRule), plain cells with four;
// elsewhere a hash picks the variant, so that the whole set shows.

#include <cstdint>

#include "tilejet/synth/internal/mix64.hpp"
#include "tilejet/synth/texture_map.hpp"

namespace tilejet::synth::detail {

// Variants of a plain combination (all four corners one colour) under VariantRule::plain_in_four.
inline constexpr uint32_t kPlainVariants = 4;

inline uint32_t combinations_of(uint32_t k) {
    return k * k * k * k;
}
// The plain combination of `colour`: that colour at all four corners.
inline uint32_t plain_combination(uint32_t k, uint32_t colour) {
    return colour * (1 + k + k * k + k * k * k);
}
// Whether `combination` has one colour at all four corners.
inline bool is_plain(uint32_t k, uint32_t combination) {
    return combination == plain_combination(k, combination % k);
}

// How many cell images a set of K corner colours, V variants and `rule` holds: K^4 V, and with
// plain_in_four 2 more for each colour, the plain combinations' variants 2 and 3.
inline size_t cell_image_count(uint32_t k, uint32_t variants, TextureMap::VariantRule rule) {
    const size_t extra = rule == TextureMap::VariantRule::plain_in_four
                             ? size_t(k) * (kPlainVariants - variants)
                             : 0;
    return size_t(combinations_of(k)) * variants + extra;
}

// Where variant `v` of `combination` sits in TextureMap::cell_images: combination + K^4 v for
// the first two (the first V), after them the plain combinations' variants 2 and 3, colour by
// colour.
inline uint32_t cell_image_slot(uint32_t k, uint32_t combination, uint32_t v) {
    if (v < 2) return combination + combinations_of(k) * v;
    return 2 * combinations_of(k) + (kPlainVariants - 2) * (combination % k) + (v - 2);
}

// The combination and variant cell image `index` shows: cell_image_slot() undone.
struct CellImageKey {
    uint32_t combination, variant;
};
inline CellImageKey cell_image_key(uint32_t k, size_t index) {
    const size_t all = combinations_of(k);
    if (index < 2 * all) return {uint32_t(index % all), uint32_t(index / all)};
    const auto extra = uint32_t(index - 2 * all), colour = extra / (kPlainVariants - 2);
    return {plain_combination(k, colour), 2 + extra % (kPlainVariants - 2)};
}

class CornerColours {
  public:
    CornerColours(const TextureMap& map, uint64_t seed)
        : k_(uint64_t(map.corner_colours)),
          variants_(map.variants),
          rule_(map.variant_rule),
          key_(hash_combine(hash_combine(map.id64(), seed), kVertexStream)),
          variant_key_(hash_combine(hash_combine(map.id64(), seed), kVariantStream)) {}

    // Uniform in [0, K) by Lemire's multiply-shift: no division, bias below 2^-60 for small K.
    uint32_t colour(int64_t i, int64_t j) const {
        if (k_ == 1) return 0;
        const uint64_t h = hash_combine(hash_combine(key_, uint64_t(i)), uint64_t(j));
        return uint32_t(uint128(h) * k_ >> 64);
    }

    // The cell image index of cell (i, j): its combination tl + K tr + K^2 bl + K^3 br, plus
    // K^4 times the variant it shows.
    uint32_t image(int64_t i, int64_t j) const {
        if (k_ == 1) return 0;
        const uint32_t c = combination(i, j);
        if (variants_ == 1) return c;
        const uint32_t v = rule_ == TextureMap::VariantRule::parity
                               ? uint32_t((i + j) & 1)
                               : twin_breaking_variant(i, j, c);
        return cell_image_slot(uint32_t(k_), c, v);
    }
    uint32_t combination(int64_t i, int64_t j) const {
        return image_of(colour(i, j), colour(i + 1, j), colour(i, j + 1), colour(i + 1, j + 1));
    }
    uint32_t image_of(uint32_t tl, uint32_t tr, uint32_t bl, uint32_t br) const {
        return uint32_t(tl + k_ * (tr + k_ * (bl + k_ * br)));
    }

  private:
    // VariantRule::break_twins and hashed. A cell none of whose eight neighbours has its
    // combination shows the first variant (break_twins) or one by hash (hashed). One with such a
    // twin across an edge shows the variant of its parity, (i + j) mod 2, as in the parity rule,
    // which differs from that of every cell across an edge; one whose twins are all across a vertex
    // shows its column's, i mod 2, which differs from theirs. Twins across an edge see each other
    // and both take the parity: none is left. Across a vertex one is left when one of the two also
    // has a twin across an edge, as where four cells around a vertex share a combination (3 x 3
    // vertices of one colour, 1 in 256), which two variants cannot part anyway.
    // VariantRule::plain_in_four: a plain cell shows one of four, with a twin anywhere round it
    // the one of its column and row parities, (i mod 2) + 2 (j mod 2), which differs from that
    // of each of its eight neighbours. Only plain cells can have twins across an edge and a vertex
    // at once (an edge twin needs both rows, or both columns, of corners alike; a vertex twin
    // a diagonal's), so every other cell keeps the rule above and no twin is left.
    uint32_t twin_breaking_variant(int64_t i, int64_t j, uint32_t c) const {
        const bool in_four =
            rule_ == TextureMap::VariantRule::plain_in_four && is_plain(uint32_t(k_), c);
        bool across_vertex = false;
        for (int64_t dj = -1; dj <= 1; ++dj)
            for (int64_t di = -1; di <= 1; ++di) {
                if ((di == 0 && dj == 0) || combination(i + di, j + dj) != c) continue;
                if (in_four) return uint32_t(i & 1) + 2 * uint32_t(j & 1);
                if (di == 0 || dj == 0) return uint32_t((i + j) & 1);
                across_vertex = true;
            }
        if (across_vertex) return uint32_t(i & 1);
        if (rule_ == TextureMap::VariantRule::break_twins) return 0;
        const uint64_t h = hash_combine(hash_combine(variant_key_, uint64_t(i)), uint64_t(j));
        return uint32_t(uint128(h) * (in_four ? uint64_t(kPlainVariants) : uint64_t(variants_)) >>
                        64);
    }

    // Keeps vertex colours independent of the activation hashes of the same map and seed.
    static constexpr uint64_t kVertexStream = 0x636f726e6572ull;     // "corner"
    static constexpr uint64_t kVariantStream = 0x76617269616e74ull;  // "variant"
    uint64_t k_;
    int variants_;
    TextureMap::VariantRule rule_;
    uint64_t key_, variant_key_;
};

}  // namespace tilejet::synth::detail
