#include "tilejet/synth/sampler.hpp"

#include "tilejet/synth/internal/active_set.hpp"
#include "tilejet/synth/internal/corner_colours.hpp"
#include "tilejet/synth/internal/diamond.hpp"
#include "tilejet/synth/internal/plane_limits.hpp"

namespace tilejet::synth {

using detail::CellGrid;

uint32_t cell_image_index(const TextureMap& map, uint64_t seed, CellIndex cell) {
    return detail::CornerColours(map, seed).image(cell.i, cell.j);
}

std::vector<uint16_t> active_patches(const TextureMap& map, uint64_t seed, CellType type,
                                     CellIndex cell) {
    std::vector<uint16_t> active;
    const uint64_t key = detail::cell_key(map.id64(), seed, 0, type, cell.i, cell.j);
    const CellImage& image = map.cell_images[cell_image_index(map, seed, cell)];
    detail::compute_active_set(image.set(type), key, active);
    return active;
}

CellIndex diamond_cell(const TextureMap& map, CellType type, int64_t x, int64_t y) {
    return CellGrid(map.cell_width, map.cell_height).cell(type, x, y);
}

Sampler::Sampler(const TextureMap& map, uint64_t seed)
    : map_(map),
      seed_(seed),
      source_step_(map.source.step[0]),
      source_elem_(map.source.elemSize()) {}

const CellImage& Sampler::image_of(CellIndex cell) const {
    return map_.cell_images[detail::CornerColours(map_, seed_).image(cell.i, cell.j)];
}

const Sampler::Memo& Sampler::memo(CellType type, CellIndex cell) {
    const size_t slot = size_t((uint64_t(cell.i) * 0x9e3779b97f4a7c15ull ^ uint64_t(cell.j)) *
                                   0xff51afd7ed558ccdull >>
                               58);
    Memo& memo = memo_[size_t(type)][slot];
    if (!(memo.cell == cell)) {
        const uint64_t key = detail::cell_key(map_.id64(), seed_, 0, type, cell.i, cell.j);
        const PatchSet& set = image_of(cell).set(type);
        detail::compute_active_set(set, key, active_);
        memo.shown.clear();
        for (uint16_t k : active_) {
            const Patch& p = set.patches[k];
            memo.shown.push_back(
                {p.x, p.y, p.width, p.height, p.row_bytes(), p.bits.data(),
                 map_.source.ptr<uint8_t>(p.src_y) + source_elem_ * size_t(p.src_x)});
        }
        memo.cell = cell;
    }
    return memo;
}

Rgb Sampler::sample(int64_t x, int64_t y) {
    const uint8_t* p = pixel(x, y);
    return {p[0], p[1], p[2]};
}

const uint8_t* Sampler::pixel(int64_t x, int64_t y) {
    detail::check_plane_point(x, y);
    const CellGrid grid(map_.cell_width, map_.cell_height);
    CellIndex cells[2];
    grid.cells(x, y, cells[0], cells[1]);
    for (CellType type : {CellType::A, CellType::B}) {
        const CellIndex cell = cells[size_t(type)];
        // Neighbouring pixels mostly share their cells: skip the memo lookup then.
        Current& current = current_[size_t(type)];
        if (!(current.cell == cell)) {
            const Memo& m = memo(type, cell);
            current = {cell, m.shown.data(), m.shown.data() + m.shown.size()};
        }
        const int64_t px = x - cell.i * grid.cell_width(), py = y - cell.j * grid.cell_height();
        for (const ShownPatch* p = current.begin; p != current.end; ++p) {
            const int64_t bx = px - p->x, by = py - p->y;
            if (bx < 0 || by < 0 || bx >= p->width || by >= p->height) continue;
            if (!mask_bit(p->bits, p->row_bytes, bx, by)) continue;
            return p->src + source_step_ * size_t(by) + source_elem_ * size_t(bx);
        }
    }
    return background(x, y);
}

const uint8_t* Sampler::background(int64_t x, int64_t y) {
    const int64_t cw = map_.cell_width, ch = map_.cell_height;
    const CellIndex cell{detail::floor_div(x, cw), detail::floor_div(y, ch)};
    if (!(background_.cell == cell)) background_ = {cell, &image_of(cell)};
    const cv::Mat& image = background_.image->pixels;
    return image.ptr<uint8_t>(int(y - cell.j * ch)) + image.elemSize() * size_t(x - cell.i * cw);
}

}  // namespace tilejet::synth
