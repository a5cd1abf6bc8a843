#pragma once

#include <cstddef>
#include <cstdint>

namespace tilejet::colour::detail {

// Total area coverage in 8-bit ink units for a limit in percent (400 % = 4 * 255).
int ink_limit_value(double percent);

// Makes C+M+Y+K <= limit for every pixel by scaling C, M and Y down together and keeping K
// (black carries the detail, and replacing colour with black is the profile's job, not ours).
// LittleCMS's ink-limiting device link does the same on a sampled grid; interpolating that grid
// can overshoot by a unit or two, and a line must never lay down more ink than the glaze takes.
void enforce_ink_limit(uint8_t* cmyk, size_t pixels, int limit);

}  // namespace tilejet::colour::detail
