#pragma once

// Integer hashing and random numbers for synth. Everything that decides which pixels a tile gets
// goes through these: 64-bit integer arithmetic only, so results are bit-exact on every
// compiler, CPU and libm (the seed paper's trig-based hash is neither fast nor reproducible).

#include <cstdint>

namespace tilejet::synth::detail {

__extension__ typedef unsigned __int128 uint128;  // GCC and Clang on 64-bit targets

inline constexpr uint64_t kGolden = 0x9e3779b97f4a7c15ull;

// splitmix64's finalizer (Stafford's mix 13): a bijection with full avalanche.
constexpr uint64_t mix64(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

constexpr uint64_t hash_combine(uint64_t h, uint64_t v) {
    return mix64(h ^ mix64(v + kGolden));
}

// A deterministic generator for the offline build (splitmix64 stream). Unlike the standard
// distributions its draws are the same with every standard library.
class Rng {
  public:
    explicit constexpr Rng(uint64_t seed) : state_(seed) {}
    constexpr uint64_t next() { return mix64(state_ += kGolden); }
    // Uniform in [0, n), n > 0 (Lemire's multiply-shift; bias below 2^-32 for our n).
    uint64_t below(uint64_t n) { return uint64_t(uint128(next()) * n >> 64); }
    int range(int lo, int hi) { return lo + int(below(uint64_t(hi - lo + 1))); }  // [lo, hi]
    double unit() { return double(next() >> 11) * 0x1.0p-53; }                    // [0, 1)

  private:
    uint64_t state_;
};

}  // namespace tilejet::synth::detail
