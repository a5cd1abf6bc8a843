#include "tilejet/quality/patch_labels.hpp"

#include <algorithm>

#include "tilejet/synth/internal/plane_limits.hpp"
#include "tilejet/synth/internal/shown_patches.hpp"

namespace tilejet::quality {

// The same walk over cells, active sets and mask runs as render_region (shown_patches.hpp),
// writing an id instead of copying source bytes; a test checks that both agree pixel for pixel.
cv::Mat render_patch_labels(const synth::TextureMap& map, uint64_t seed,
                            const synth::Region& region) {
    synth::detail::check_region(region);
    cv::Mat labels(region.height, region.width, CV_32S, cv::Scalar(0));
    if (region.width == 0 || region.height == 0) return labels;
    const int64_t x0 = region.x, y0 = region.y;
    int32_t id = 0;
    synth::detail::for_each_shown_run(
        map, seed, x0, x0 + region.width, y0, y0 + region.height,
        [&](const synth::Patch&, int64_t, int64_t) { ++id; },
        [&](int64_t y, int64_t a, int64_t b) {
            int32_t* row = labels.ptr<int32_t>(int(y - y0));
            std::fill(row + (a - x0), row + (b - x0), id);
        });
    return labels;
}

}  // namespace tilejet::quality
