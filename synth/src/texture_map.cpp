#include "tilejet/synth/texture_map.hpp"

#include <cmath>
#include <limits>

namespace tilejet::synth {

void Patch::derive_runs() {
    runs.clear();
    row_runs.assign(size_t(height) + 1, 0);
    for (int r = 0; r < height; ++r) {
        row_runs[size_t(r)] = uint32_t(runs.size());
        for (int c = 0; c < width;) {
            if (!covers(c, r)) {
                ++c;
                continue;
            }
            const int start = c;
            while (c < width && covers(c, r))
                ++c;
            runs.push_back({uint16_t(r), uint16_t(start), uint16_t(c - start)});
        }
    }
    row_runs[size_t(height)] = uint32_t(runs.size());
}

uint64_t TextureMap::id64() const {
    uint64_t v = 0;
    for (int b = 7; b >= 0; --b)
        v = (v << 8) | id[size_t(b)];
    return v;
}

std::string TextureMap::id_hex() const {
    static const char digits[] = "0123456789abcdef";
    std::string s;
    for (uint8_t b : id)
        s += digits[b >> 4], s += digits[b & 15];
    return s;
}

uint64_t activation_threshold(double active_per_cell, size_t set_size) {
    if (set_size == 0 || !(active_per_cell > 0)) return 0;
    const double eta = active_per_cell / double(set_size);
    if (eta >= 1) return std::numeric_limits<uint64_t>::max();
    return uint64_t(std::ldexp(eta, 64));
}

}  // namespace tilejet::synth
