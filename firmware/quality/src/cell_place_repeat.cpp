#include "tilejet/quality/cell_place_repeat.hpp"

#include <algorithm>
#include <cstring>
#include <vector>

#include "tilejet/quality/cell_stretch.hpp"
#include "tilejet/synth/sampler.hpp"

namespace tilejet::quality {

namespace {

// Places looked at per cell side, at most: every place of cells up to this size, every
// second, third... of larger ones, so that an 8192 px cell costs what a 256 px one does.
constexpr int kMostPlaces = 256;

}  // namespace

CellPlaceRepeat cell_place_repeat(const synth::TextureMap& map, uint64_t seed) {
    const int cw = map.cell_width, ch = map.cell_height;
    const int across = cells_along(cw, kWideStretch), down = cells_along(ch, kWideStretch);
    const int step = (std::max(cw, ch) + kMostPlaces - 1) / kMostPlaces;
    std::vector<int> us, vs;
    for (int u = 0; u < cw; u += step)
        us.push_back(u);
    for (int v = 0; v < ch; v += step)
        vs.push_back(v);
    CellPlaceRepeat r;
    r.cells = across * down;
    r.band = std::max(1, std::min(cw, ch) / 10);
    // Cell by cell, as sampling runs fastest (a cell's patches stay at hand): per place, the
    // cells' pixels, 3 bytes of R,G,B or 4 of C,M,Y,K in one uint32 each.
    const size_t places = us.size() * vs.size(), bytes = map.source.elemSize();
    std::vector<uint32_t> seen(places * size_t(r.cells));
    synth::Sampler sampler(map, seed);
    for (int j = 0, cell = 0; j < down; ++j)
        for (int i = 0; i < across; ++i, ++cell)
            for (size_t b = 0; b < vs.size(); ++b)
                for (size_t a = 0; a < us.size(); ++a) {
                    uint32_t value = 0;
                    std::memcpy(&value,
                                sampler.pixel(int64_t(i) * cw + us[a], int64_t(j) * ch + vs[b]),
                                bytes);
                    seen[(b * us.size() + a) * size_t(r.cells) + size_t(cell)] = value;
                }
    double border = 0, inside = 0;
    int64_t border_places = 0, inside_places = 0;
    for (size_t b = 0; b < vs.size(); ++b)
        for (size_t a = 0; a < us.size(); ++a) {
            const auto first = seen.begin() + std::ptrdiff_t((b * us.size() + a) * size_t(r.cells));
            const auto last = first + r.cells;
            std::sort(first, last);
            std::ptrdiff_t most = 1;
            for (auto x = first, y = first; x != last; x = y) {
                while (y != last && *y == *x)
                    ++y;
                most = std::max(most, y - x);
            }
            const double share = double(most) / double(r.cells);
            const int u = us[a], v = vs[b];
            const bool in_band = u < r.band || v < r.band || u >= cw - r.band || v >= ch - r.band;
            (in_band ? border : inside) += share;
            ++(in_band ? border_places : inside_places);
        }
    r.border = border_places ? border / double(border_places) : 0;
    r.inside = inside_places ? inside / double(inside_places) : r.border;
    return r;
}

}  // namespace tilejet::quality
