#include <algorithm>
#include <cstring>
#include <thread>
#include <vector>

#include "diamond.hpp"
#include "plane_limits.hpp"
#include "shown_patches.hpp"
#include "tilejet/synth/sampler.hpp"

namespace tilejet::synth {

namespace {

using detail::CellGrid;
using detail::floor_mod;

// Rows [row0, row1) of the region: first the cell image everywhere, then every active patch
// of every cell whose diamond reaches the band, run by run. Patches never overlap one another
// (diamonds, the A/B split and overlap removal see to that), so the order of the copies does
// not matter and the bytes equal Sampler::sample's.
void render_band(const TextureMap& map, uint64_t seed, const Region& region, int row0, int row1,
                 uint8_t* rgb, size_t stride) {
    const CellGrid grid(map.cell_width, map.cell_height);
    const int64_t cw = grid.cell_width(), ch = grid.cell_height();
    const CellImage& image = map.cell_images.front();

    const int64_t px_bytes = int64_t(map.source.elemSize());  // 3 for RGB, 4 for CMYK
    const int64_t x0 = region.x, x1 = region.x + region.width;
    for (int r = row0; r < row1; ++r) {
        const uint8_t* cell_row = image.rgb.ptr<uint8_t>(int(floor_mod(region.y + r, ch)));
        uint8_t* dst = rgb + size_t(r) * stride;
        int64_t offset = floor_mod(x0, cw);
        for (int64_t left = region.width; left > 0;) {
            const int64_t n = std::min(cw - offset, left);
            std::memcpy(dst, cell_row + px_bytes * offset, size_t(px_bytes * n));
            dst += px_bytes * n, left -= n, offset = 0;
        }
    }

    const Patch* patch = nullptr;
    int64_t patch_x = 0, patch_y = 0;
    detail::for_each_shown_run(
        map, seed, x0, x1, region.y + row0, region.y + row1,
        [&](const Patch& p, int64_t px, int64_t py) { patch = &p, patch_x = px, patch_y = py; },
        [&](int64_t y, int64_t a, int64_t b) {
            const uint8_t* src = map.source.ptr<uint8_t>(patch->src_y + int(y - patch_y));
            std::memcpy(rgb + size_t(y - region.y) * stride + px_bytes * (a - x0),
                        src + px_bytes * (patch->src_x + (a - patch_x)),
                        size_t(px_bytes * (b - a)));
        });
}

}  // namespace

void render_region(const TextureMap& map, uint64_t seed, const Region& region, uint8_t* rgb,
                   size_t stride, int threads) {
    detail::check_region(region);
    if (region.width == 0 || region.height == 0) return;
    if (stride < size_t(region.width) * map.source.elemSize())
        throw SynthError("row stride " + std::to_string(stride) + " is shorter than a row");

    if (threads <= 0) threads = int(std::max(1u, std::thread::hardware_concurrency()));
    const int bands = std::min(threads, region.height);
    if (bands == 1) return render_band(map, seed, region, 0, region.height, rgb, stride);

    std::vector<std::jthread> workers;
    workers.reserve(size_t(bands));
    for (int b = 0; b < bands; ++b) {
        const int row0 = int(int64_t(region.height) * b / bands);
        const int row1 = int(int64_t(region.height) * (b + 1) / bands);
        workers.emplace_back(
            [&, row0, row1] { render_band(map, seed, region, row0, row1, rgb, stride); });
    }
}

cv::Mat render_region(const TextureMap& map, uint64_t seed, const Region& region, int threads) {
    detail::check_region(region);
    cv::Mat out(region.height, region.width, map.source.type());
    render_region(map, seed, region, out.data, out.step[0], threads);
    return out;
}

}  // namespace tilejet::synth
