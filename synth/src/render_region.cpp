#include <algorithm>
#include <cstring>
#include <optional>
#include <thread>
#include <vector>

#include "stream_copy.hpp"
#include "tilejet/synth/internal/corner_colours.hpp"
#include "tilejet/synth/internal/diamond.hpp"
#include "tilejet/synth/internal/plane_limits.hpp"
#include "tilejet/synth/internal/shown_patches.hpp"
#include "tilejet/synth/sampler.hpp"

namespace tilejet::synth {

namespace {

using detail::CellGrid;
using detail::floor_mod;

// What one strip of rows may take: both of its passes stay in the core's own cache (L2).
constexpr size_t kStripBytes = 256 * 1024;

// Rows [row0, row1) of the region, a strip of rows at a time. Each strip is composed in a
// cache-sized scratch buffer, first the cell image everywhere and then every active patch of
// every cell whose diamond reaches it, run by run, and then streamed out once (stream_copy.hpp).
// Patches never overlap one another (diamonds, the A/B split and overlap removal see to that),
// so the order of the copies does not matter and the bytes equal Sampler::sample's.
void render_band(const TextureMap& map, uint64_t seed, const Region& region, int row0, int row1,
                 uint8_t* out, size_t stride) {
    const CellGrid grid(map.cell_width, map.cell_height);
    const int64_t cw = grid.cell_width(), ch = grid.cell_height();
    const detail::CornerColours colours(map, seed);
    const int64_t px_bytes = int64_t(map.source.elemSize());  // 3 for RGB, 4 for CMYK
    const int64_t x0 = region.x, x1 = region.x + region.width;
    const size_t row_bytes = size_t(px_bytes * region.width);

    // The band's patches once (the cell walk costs too much to repeat per strip), each filed
    // under the first strip it reaches by a counting sort: std::sort on the strip number made a
    // 600 mm, 360 dpi tile 4-8 ms slower (tilejet-daemon-bench).
    struct Shown {
        const Patch* patch;
        int64_t x, y;
    };
    const int strip_rows = int(std::max<size_t>(1, kStripBytes / row_bytes));
    const int strips = (row1 - row0 + strip_rows - 1) / strip_rows;
    const int64_t band_y0 = region.y + row0;
    const auto first_strip = [&](const Shown& s) {
        return size_t((std::max(s.y, band_y0) - band_y0) / strip_rows);
    };
    std::vector<Shown> shown;
    detail::for_each_shown_patch(map, seed, x0, x1, band_y0, region.y + row1,
                                 [&](const Patch& p, int64_t px, int64_t py) {
                                     shown.push_back({&p, px, py});
                                 });
    std::vector<size_t> filed_from(size_t(strips) + 1, 0);
    for (const Shown& s : shown)
        ++filed_from[first_strip(s) + 1];
    for (size_t k = 1; k < filed_from.size(); ++k)
        filed_from[k] += filed_from[k - 1];
    std::vector<Shown> filed(shown.size());
    {
        std::vector<size_t> next(filed_from.begin(), filed_from.end() - 1);
        for (const Shown& s : shown)
            filed[next[first_strip(s)]++] = s;
    }

    // The cell images of the band's cells, a row of cells at a time: the vertex hashes cost
    // too much to repeat per pixel row.
    const int64_t first_column = detail::floor_div(x0, cw);
    const size_t columns = size_t(detail::floor_div(x1 - 1, cw) - first_column + 1);
    std::vector<const cv::Mat*> row_images(columns);
    std::optional<int64_t> images_row;  // the row of cells row_images holds

    std::vector<uint8_t> strip(size_t(strip_rows) * row_bytes);
    std::vector<Shown> reaching;  // patches that reach the current strip, and maybe beyond
    for (int k = 0; k < strips; ++k) {
        const int s0 = row0 + k * strip_rows, s1 = std::min(row1, s0 + strip_rows);
        const int64_t y0 = region.y + s0, y1 = region.y + s1;
        for (int64_t y = y0; y < y1; ++y) {
            const int64_t cell_j = detail::floor_div(y, ch);
            if (images_row != cell_j) {
                for (size_t c = 0; c < columns; ++c)
                    row_images[c] =
                        &map.cell_images[colours.image(first_column + int64_t(c), cell_j)].pixels;
                images_row = cell_j;
            }
            const int cell_y = int(y - cell_j * ch);
            uint8_t* dst = strip.data() + size_t(y - y0) * row_bytes;
            int64_t offset = floor_mod(x0, cw);
            size_t column = 0;
            for (int64_t left = region.width; left > 0; ++column) {
                const int64_t n = std::min(cw - offset, left);
                std::memcpy(dst, row_images[column]->ptr<uint8_t>(cell_y) + px_bytes * offset,
                            size_t(px_bytes * n));
                dst += px_bytes * n, left -= n, offset = 0;
            }
        }
        std::erase_if(reaching, [&](const Shown& s) { return s.y + s.patch->height <= y0; });
        reaching.insert(reaching.end(), filed.begin() + std::ptrdiff_t(filed_from[size_t(k)]),
                        filed.begin() + std::ptrdiff_t(filed_from[size_t(k) + 1]));
        for (const Shown& s : reaching) {
            const Patch& p = *s.patch;
            detail::for_each_run(p, s.x, s.y, x0, x1, y0, y1, [&](int64_t y, int64_t a, int64_t b) {
                const uint8_t* src = map.source.ptr<uint8_t>(p.src_y + int(y - s.y));
                std::memcpy(strip.data() + size_t(y - y0) * row_bytes + px_bytes * (a - x0),
                            src + px_bytes * (p.src_x + (a - s.x)), size_t(px_bytes * (b - a)));
            });
        }
        for (int r = s0; r < s1; ++r)
            detail::stream_copy(out + size_t(r) * stride, strip.data() + size_t(r - s0) * row_bytes,
                                row_bytes);
    }
    detail::stream_fence();
}

}  // namespace

void render_region(const TextureMap& map, uint64_t seed, const Region& region, uint8_t* out,
                   size_t stride, int threads) {
    detail::check_region(region);
    if (region.width == 0 || region.height == 0) return;
    if (stride < size_t(region.width) * map.source.elemSize())
        throw SynthError("row stride " + std::to_string(stride) + " is shorter than a row");

    if (threads <= 0) threads = int(std::max(1u, std::thread::hardware_concurrency()));
    const int bands = std::min(threads, region.height);
    if (bands == 1) return render_band(map, seed, region, 0, region.height, out, stride);

    std::vector<std::jthread> workers;
    workers.reserve(size_t(bands));
    for (int b = 0; b < bands; ++b) {
        const int row0 = int(int64_t(region.height) * b / bands);
        const int row1 = int(int64_t(region.height) * (b + 1) / bands);
        workers.emplace_back(
            [&, row0, row1] { render_band(map, seed, region, row0, row1, out, stride); });
    }
}

cv::Mat render_region(const TextureMap& map, uint64_t seed, const Region& region, int threads) {
    detail::check_region(region);
    cv::Mat out(region.height, region.width, map.source.type());
    render_region(map, seed, region, out.data, out.step[0], threads);
    return out;
}

}  // namespace tilejet::synth
