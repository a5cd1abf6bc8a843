#pragma once

#include <cstdint>
#include <string>

#include "tilejet/synth/error.hpp"
#include "tilejet/synth/sampler.hpp"

namespace tilejet::synth::detail {

// The plane is promised to at least +-2^31; +-2^40 keeps every intermediate of the diamond
// arithmetic (coordinates times twice the cell size) exact in 64-bit integers and doubles.
inline constexpr int64_t kPlaneLimit = int64_t(1) << 40;

inline void check_plane_point(int64_t x, int64_t y) {
    if (x < -kPlaneLimit || x > kPlaneLimit || y < -kPlaneLimit || y > kPlaneLimit)
        throw SynthError("point (" + std::to_string(x) + ", " + std::to_string(y) +
                         ") is outside the texture plane (|x|, |y| <= 2^40)");
}

// A region's size is not negative and its corners lie in the plane.
inline void check_region(const Region& region) {
    if (region.width < 0 || region.height < 0)
        throw SynthError("region size " + std::to_string(region.width) + "x" +
                         std::to_string(region.height) + " is negative");
    check_plane_point(region.x, region.y);
    check_plane_point(region.x + region.width, region.y + region.height);
}

}  // namespace tilejet::synth::detail
