#include "tilejet/synth/patch_coverage.hpp"

#include "../plane_limits.hpp"
#include "../shown_patches.hpp"

namespace tilejet::synth {

// Counts run lengths rather than rendering labels: the same walk as render_region, so it
// agrees with what is printed, and no region-sized buffer, so a large region costs only its
// patches. Shown patches never overlap, so the run lengths add up without double counting.
double patch_coverage(const TextureMap& map, uint64_t seed, const Region& region) {
    detail::check_region(region);
    if (region.width == 0 || region.height == 0)
        throw SynthError("patch coverage of an empty region");
    const int64_t x0 = region.x, y0 = region.y;
    int64_t covered = 0;
    detail::for_each_shown_run(
        map, seed, x0, x0 + region.width, y0, y0 + region.height,
        [](const Patch&, int64_t, int64_t) {},
        [&](int64_t, int64_t a, int64_t b) { covered += b - a; });
    return double(covered) / (double(region.width) * double(region.height));
}

}  // namespace tilejet::synth
