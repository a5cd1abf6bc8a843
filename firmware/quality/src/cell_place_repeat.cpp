#include "tilejet/quality/cell_place_repeat.hpp"

#include <algorithm>
#include <cstring>
#include <vector>

#include "tilejet/synth/sampler.hpp"

namespace tilejet::quality {

namespace {

constexpr int kMostCells = 16, kFewestCells = 4, kMostSide = 4096;

}  // namespace

CellPlaceRepeat cell_place_repeat(const synth::TextureMap& map, uint64_t seed) {
    const int cw = map.cell_width, ch = map.cell_height;
    const int across = std::clamp(kMostSide / cw, kFewestCells, kMostCells);
    const int down = std::clamp(kMostSide / ch, kFewestCells, kMostCells);
    const cv::Mat plane = synth::render_region(map, seed, {0, 0, across * cw, down * ch});
    const size_t bytes = plane.elemSize();  // 3 for R,G,B, 4 for C,M,Y,K: one uint32 each
    CellPlaceRepeat r;
    r.cells = across * down;
    r.band = std::max(1, std::min(cw, ch) / 10);
    std::vector<uint32_t> values(size_t(r.cells));
    double border = 0, inside = 0;
    int64_t border_places = 0, inside_places = 0;
    for (int v = 0; v < ch; ++v)
        for (int u = 0; u < cw; ++u) {
            size_t n = 0;
            for (int j = 0; j < down; ++j)
                for (int i = 0; i < across; ++i) {
                    uint32_t value = 0;
                    std::memcpy(&value, plane.ptr<uint8_t>(j * ch + v) + bytes * size_t(i * cw + u),
                                bytes);
                    values[n++] = value;
                }
            std::sort(values.begin(), values.end());
            size_t most = 1;
            for (size_t a = 0, b = 0; a < n; a = b) {
                while (b < n && values[b] == values[a])
                    ++b;
                most = std::max(most, b - a);
            }
            const double share = double(most) / double(n);
            const bool in_band = u < r.band || v < r.band || u >= cw - r.band || v >= ch - r.band;
            (in_band ? border : inside) += share;
            ++(in_band ? border_places : inside_places);
        }
    r.border = border_places ? border / double(border_places) : 0;
    r.inside = inside_places ? inside / double(inside_places) : r.border;
    return r;
}

}  // namespace tilejet::quality
