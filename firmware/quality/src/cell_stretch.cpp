#include "tilejet/quality/cell_stretch.hpp"

#include "tilejet/synth/sampler.hpp"

namespace tilejet::quality {

cv::Mat cell_stretch_plane(const synth::TextureMap& map, uint64_t seed, const CellStretch& stretch,
                           int threads) {
    const int across = cells_along(map.cell_width, stretch);
    const int down = cells_along(map.cell_height, stretch);
    return synth::render_region(map, seed, {0, 0, across * map.cell_width, down * map.cell_height},
                                threads);
}

}  // namespace tilejet::quality
