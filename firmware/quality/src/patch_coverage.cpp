#include "tilejet/quality/patch_coverage.hpp"

#include "tilejet/synth/internal/plane_limits.hpp"
#include "tilejet/synth/internal/shown_patches.hpp"

namespace tilejet::quality {

// Counts run lengths rather than rendering labels: the same walk as render_region, so it
// agrees with what is printed, and no region-sized buffer, so a large region costs only its
// patches. Shown patches never overlap, so the run lengths add up without double counting.
double patch_coverage(const synth::TextureMap& map, uint64_t seed, const synth::Region& region) {
    synth::detail::check_region(region);
    if (region.width == 0 || region.height == 0)
        throw synth::SynthError("patch coverage of an empty region");
    const int64_t x0 = region.x, y0 = region.y;
    int64_t covered = 0;
    synth::detail::for_each_shown_run(
        map, seed, x0, x0 + region.width, y0, y0 + region.height,
        [](const synth::Patch&, int64_t, int64_t) {},
        [&](int64_t, int64_t a, int64_t b) { covered += b - a; });
    return double(covered) / (double(region.width) * double(region.height));
}

}  // namespace tilejet::quality
