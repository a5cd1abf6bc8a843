#pragma once

// One tile's separations: 8-bit C,M,Y,K interleaved rows, the bytes the heads get. The same
// (map, profile, seed, index, size) always gives the same bytes, so a reprint after a crash or
// an e-stop is bit-identical.
#include <cstdint>
#include <vector>

namespace tilejet::daemon {

struct Separations {
    std::int64_t job = 0;
    std::int64_t index = 0;
    int width = 0, height = 0;
    std::vector<std::uint8_t> bytes;
};

}  // namespace tilejet::daemon
