#pragma once

// Cell diamonds (docs/design.md sections 2.5 and 3.1). Cell (i, j) covers [i*Cx, (i+1)*Cx) x
// [j*Cy, (j+1)*Cy); it is of type A when i + j is even. The diamond of a cell is
// |dx|/Cx + |dy|/Cy <= 1 around its centre. Rotated to u = x/Cx + y/Cy, v = x/Cx - y/Cy the
// diamonds of one type become an axis-aligned grid of 2 x 2 squares, so finding a pixel's cell is
// two floor divisions. All of it is done in integers scaled by 2*Cx*Cy on pixel centres, so every
// pixel belongs to exactly one A diamond and one B diamond, with no floating point at all.

#include <cstdint>

#include "tilejet/synth/sampler.hpp"

namespace tilejet::synth::detail {

// floor(a / b) for b > 0. The quotient is estimated in double (exact enough for |a| < 2^52)
// and corrected in integers, which is several times faster than a 64-bit division.
inline int64_t floor_div(int64_t a, int64_t b) {
    auto q = int64_t(double(a) / double(b));
    int64_t r = a - q * b;
    if (r < 0) {
        do {
            --q, r += b;
        } while (r < 0);
    } else {
        while (r >= b)
            ++q, r -= b;
    }
    return q;
}

inline int64_t floor_mod(int64_t a, int64_t b) {
    int64_t r = a % b;
    return r < 0 ? r + b : r;
}

class CellGrid {
  public:
    CellGrid(int cell_width, int cell_height)
        : cx_(cell_width), cy_(cell_height), d_(4 * cx_ * cy_) {}

    int64_t cell_width() const { return cx_; }
    int64_t cell_height() const { return cy_; }

    CellIndex a_cell(int64_t x, int64_t y) const {
        const int64_t u = (2 * x + 1) * cy_ + (2 * y + 1) * cx_;
        const int64_t v = (2 * x + 1) * cy_ - (2 * y + 1) * cx_;
        const int64_t m = floor_div(u, d_), n = floor_div(v + d_ / 2, d_);
        return {m + n, m - n};
    }
    CellIndex b_cell(int64_t x, int64_t y) const {
        const int64_t u = (2 * x + 1) * cy_ + (2 * y + 1) * cx_;
        const int64_t v = (2 * x + 1) * cy_ - (2 * y + 1) * cx_;
        const int64_t m = floor_div(u + d_ / 2, d_), n = floor_div(v, d_);
        return {m + n, m - n - 1};
    }
    CellIndex cell(CellType type, int64_t x, int64_t y) const {
        return type == CellType::A ? a_cell(x, y) : b_cell(x, y);
    }
    // Both cells at once with two divisions instead of four: the A and B grids are offset by
    // half a period, so both floors follow from floor(u / (D/2)) and floor(v / (D/2)).
    void cells(int64_t x, int64_t y, CellIndex& a, CellIndex& b) const {
        const int64_t u = (2 * x + 1) * cy_ + (2 * y + 1) * cx_;
        const int64_t v = (2 * x + 1) * cy_ - (2 * y + 1) * cx_;
        const int64_t q = floor_div(u, d_ / 2), r = floor_div(v, d_ / 2);
        const int64_t ma = q >> 1, na = (r + 1) >> 1, mb = (q + 1) >> 1, nb = r >> 1;
        a = {ma + na, ma - na};
        b = {mb + nb, mb - nb - 1};
    }

    // Whether cell-relative pixel (px, py) lies strictly inside its cell's diamond. A patch
    // whose pixels all pass can be shown in any cell of either type: strict interiors of
    // same-type diamonds are disjoint, whichever way the diamonds' shared edges are assigned.
    bool in_diamond_interior(int64_t px, int64_t py) const {
        const int64_t ax = 2 * px + 1 - cx_, ay = 2 * py + 1 - cy_;
        return (ax < 0 ? -ax : ax) * cy_ + (ay < 0 ? -ay : ay) * cx_ < 2 * cx_ * cy_;
    }

  private:
    int64_t cx_, cy_, d_;
};

}  // namespace tilejet::synth::detail
