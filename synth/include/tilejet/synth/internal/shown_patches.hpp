#pragma once

// The walk every region-wide operation shares: the cells whose diamonds reach a rectangle of
// the plane, their shown patches (activation, overlap removal), and each patch's mask runs
// clipped to the rectangle. region_render copies source bytes along the runs; patch labels
// write an id.

#include <algorithm>
#include <cstdint>
#include <vector>

#include "tilejet/synth/internal/active_set.hpp"
#include "tilejet/synth/internal/corner_colours.hpp"
#include "tilejet/synth/internal/diamond.hpp"
#include "tilejet/synth/texture_map.hpp"

namespace tilejet::synth::detail {

// For every shown patch that reaches [x0, x1) x [y0, y1): on_patch(patch, px, py) with the
// patch's bounding-box corner on the plane. Patches never overlap one another.
template <typename OnPatch>
void for_each_shown_patch(const TextureMap& map, uint64_t seed, int64_t x0, int64_t x1, int64_t y0,
                          int64_t y1, OnPatch&& on_patch) {
    const int64_t cw = map.cell_width, ch = map.cell_height;
    const CornerColours colours(map, seed);
    const uint64_t map_id = map.id64();
    std::vector<uint16_t> active;
    for (CellType type : {CellType::A, CellType::B}) {
        // A diamond reaches at most one cell size beyond its cell on every side.
        for (int64_t j = floor_div(y0, ch) - 1; j <= floor_div(y1 - 1, ch) + 1; ++j) {
            for (int64_t i = floor_div(x0, cw) - 1; i <= floor_div(x1 - 1, cw) + 1; ++i) {
                if (((i + j) & 1) != int64_t(type)) continue;
                const PatchSet& set = map.cell_images[colours.image(i, j)].set(type);
                compute_active_set(set, cell_key(map_id, seed, 0, type, i, j), active);
                for (uint16_t k : active) {
                    const Patch& p = set.patches[k];
                    const int64_t px = i * cw + p.x, py = j * ch + p.y;
                    if (std::max(py, y0) >= std::min(py + p.height, y1) || px >= x1 ||
                        px + p.width <= x0)
                        continue;
                    on_patch(p, px, py);
                }
            }
        }
    }
}

// on_run(y, a, b) for each mask run of patch p (corner px, py on the plane) clipped to
// [x0, x1) x [y0, y1): plane row y, columns [a, b).
template <typename OnRun>
void for_each_run(const Patch& p, int64_t px, int64_t py, int64_t x0, int64_t x1, int64_t y0,
                  int64_t y1, OnRun&& on_run) {
    const int64_t top = std::max(py, y0), bottom = std::min(py + p.height, y1);
    for (int64_t y = top; y < bottom; ++y) {
        const size_t row = size_t(y - py);
        for (uint32_t q = p.row_runs[row]; q < p.row_runs[row + 1]; ++q) {
            const MaskRun& run = p.runs[q];
            const int64_t a = std::max(px + run.x, x0);
            const int64_t b = std::min(px + run.x + run.length, x1);
            if (a < b) on_run(y, a, b);
        }
    }
}

// Both walks at once: on_patch as for_each_shown_patch, then that patch's runs.
template <typename OnPatch, typename OnRun>
void for_each_shown_run(const TextureMap& map, uint64_t seed, int64_t x0, int64_t x1, int64_t y0,
                        int64_t y1, OnPatch&& on_patch, OnRun&& on_run) {
    for_each_shown_patch(map, seed, x0, x1, y0, y1, [&](const Patch& p, int64_t px, int64_t py) {
        on_patch(p, px, py);
        for_each_run(p, px, py, x0, x1, y0, y1, on_run);
    });
}

}  // namespace tilejet::synth::detail
