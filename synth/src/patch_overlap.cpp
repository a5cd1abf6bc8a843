#include "patch_overlap.hpp"

#include <algorithm>

namespace tilejet::synth::detail {

bool patches_overlap(const Patch& a, const Patch& b, int dx, int dy) {
    const int bx = b.x + dx, by = b.y + dy;
    const int top = std::max(a.y, by), bottom = std::min(a.y + a.height, by + b.height);
    if (top >= bottom || std::max(a.x, bx) >= std::min(a.x + a.width, bx + b.width)) return false;
    for (int y = top; y < bottom; ++y) {
        const size_t ra = size_t(y - a.y), rb = size_t(y - by);
        uint32_t i = a.row_runs[ra], j = b.row_runs[rb];
        const uint32_t i_end = a.row_runs[ra + 1], j_end = b.row_runs[rb + 1];
        while (i < i_end && j < j_end) {  // runs of a row are sorted and disjoint
            const int a0 = a.x + a.runs[i].x, a1 = a0 + a.runs[i].length;
            const int b0 = bx + b.runs[j].x, b1 = b0 + b.runs[j].length;
            if (a0 < b1 && b0 < a1) return true;
            if (a1 <= b1)
                ++i;
            else
                ++j;
        }
    }
    return false;
}

}  // namespace tilejet::synth::detail
