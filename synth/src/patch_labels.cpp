#include "tilejet/synth/patch_labels.hpp"

#include <algorithm>

#include "active_set.hpp"
#include "diamond.hpp"
#include "plane_limits.hpp"

namespace tilejet::synth {

// The same walk over cells, active sets and mask runs as render_region's render_band, writing
// an id instead of copying source bytes; a test checks that both agree pixel for pixel.
cv::Mat render_patch_labels(const TextureMap& map, uint64_t seed, const Region& region) {
    if (region.width < 0 || region.height < 0)
        throw SynthError("region size " + std::to_string(region.width) + "x" +
                         std::to_string(region.height) + " is negative");
    detail::check_plane_point(region.x, region.y);
    detail::check_plane_point(region.x + region.width, region.y + region.height);
    cv::Mat labels(region.height, region.width, CV_32S, cv::Scalar(0));
    if (region.width == 0 || region.height == 0) return labels;

    using detail::floor_div;
    const int64_t cw = map.cell_width, ch = map.cell_height;
    const CellImage& image = map.cell_images.front();
    const int64_t x0 = region.x, x1 = region.x + region.width;
    const int64_t y0 = region.y, y1 = region.y + region.height;
    const uint64_t map_id = map.id64();
    int32_t next_id = 1;
    std::vector<uint16_t> active;
    for (CellType type : {CellType::A, CellType::B}) {
        const PatchSet& set = image.set(type);
        for (int64_t j = floor_div(y0, ch) - 1; j <= floor_div(y1 - 1, ch) + 1; ++j) {
            for (int64_t i = floor_div(x0, cw) - 1; i <= floor_div(x1 - 1, cw) + 1; ++i) {
                if (((i + j) & 1) != int64_t(type)) continue;
                detail::compute_active_set(set, detail::cell_key(map_id, seed, 0, type, i, j),
                                           active);
                for (uint16_t k : active) {
                    const Patch& p = set.patches[k];
                    const int64_t px = i * cw + p.x, py = j * ch + p.y;
                    const int64_t top = std::max(py, y0), bottom = std::min(py + p.height, y1);
                    if (top >= bottom || px >= x1 || px + p.width <= x0) continue;
                    const int32_t id = next_id++;
                    for (int64_t y = top; y < bottom; ++y) {
                        const int row = int(y - py);
                        int32_t* dst = labels.ptr<int32_t>(int(y - y0));
                        for (uint32_t q = p.row_runs[size_t(row)]; q < p.row_runs[size_t(row) + 1];
                             ++q) {
                            const MaskRun& run = p.runs[q];
                            const int64_t a = std::max(px + run.x, x0);
                            const int64_t b = std::min(px + run.x + run.length, x1);
                            std::fill(dst + (a - x0), dst + std::max(a, b) - x0, id);
                        }
                    }
                }
            }
        }
    }
    return labels;
}

}  // namespace tilejet::synth
