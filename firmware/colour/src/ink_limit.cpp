#include "ink_limit.hpp"

#include <algorithm>
#include <cmath>

namespace tilejet::colour::detail {

int ink_limit_value(double percent) {
    return std::clamp(int(std::floor(percent / 100.0 * 255.0 + 1e-9)), 0, 4 * 255);
}

void enforce_ink_limit(uint8_t* cmyk, size_t pixels, int limit) {
    for (size_t i = 0; i < pixels; ++i, cmyk += 4) {
        const int c = cmyk[0], m = cmyk[1], y = cmyk[2], k = cmyk[3];
        const int total = c + m + y + k;
        if (total <= limit) continue;
        if (k >= limit) {
            cmyk[0] = cmyk[1] = cmyk[2] = 0;
            cmyk[3] = uint8_t(limit);
            continue;
        }
        // Floor division keeps the sum at or under the limit.
        const int room = limit - k, cmy = c + m + y;
        cmyk[0] = uint8_t(c * room / cmy);
        cmyk[1] = uint8_t(m * room / cmy);
        cmyk[2] = uint8_t(y * room / cmy);
    }
}

}  // namespace tilejet::colour::detail
