#pragma once

#include <cstdint>
#include <string>

#include "tilejet/synth/error.hpp"

namespace tilejet::synth::detail {

// The plane is promised to at least +-2^31; +-2^40 keeps every intermediate of the diamond
// arithmetic (coordinates times twice the cell size) exact in 64-bit integers and doubles.
inline constexpr int64_t kPlaneLimit = int64_t(1) << 40;

inline void check_plane_point(int64_t x, int64_t y) {
    if (x < -kPlaneLimit || x > kPlaneLimit || y < -kPlaneLimit || y > kPlaneLimit)
        throw SynthError("point (" + std::to_string(x) + ", " + std::to_string(y) +
                         ") is outside the texture plane (|x|, |y| <= 2^40)");
}

}  // namespace tilejet::synth::detail
