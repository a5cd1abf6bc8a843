#include "tilejet/quality/cell_place_energy.hpp"

#include <algorithm>
#include <vector>

#include "tilejet/synth/error.hpp"
#include "tilejet/synth/internal/mix64.hpp"
#include "tilejet/synth/sampler.hpp"

namespace tilejet::quality {

CellPlaceEnergy cell_place_energy(const cv::Mat& plane, cv::Size cell, const TextureEnergy& energy,
                                  size_t samples, uint64_t seed) {
    if (cell.width < 1 || cell.height < 1 || plane.cols < kEnergyPatch || plane.rows < kEnergyPatch)
        throw synth::SynthError("cell place energy needs cells and a plane of at least 8x8 px");
    CellPlaceEnergy r;
    r.band = std::max(1, std::min(cell.width, cell.height) / 10);
    // Patches are drawn at random and sorted by where their centre falls, until each kind has
    // `samples` (or the draws run out: a plane all border).
    std::vector<cv::Mat> border, inside;
    synth::detail::Rng rng(synth::detail::hash_combine(seed, 0xce11ull));
    for (size_t draw = 0;
         draw < 64 * samples && (border.size() < samples || inside.size() < samples); ++draw) {
        const int x = rng.range(0, plane.cols - kEnergyPatch),
                  y = rng.range(0, plane.rows - kEnergyPatch);
        const int u = (x + kEnergyPatch / 2) % cell.width, v = (y + kEnergyPatch / 2) % cell.height;
        const int from_edge = std::min({u, v, cell.width - u, cell.height - v});
        std::vector<cv::Mat>& kind = from_edge < r.band ? border : inside;
        if (kind.size() < samples)
            kind.push_back(plane(cv::Rect(x, y, kEnergyPatch, kEnergyPatch)));
    }
    r.border = energy.measure(border, border.size(), seed);
    r.inside = energy.measure(inside, inside.size(), seed);
    return r;
}

cv::Mat cell_place_plane(const synth::TextureMap& map, uint64_t seed, int threads) {
    return cell_stretch_plane(map, seed, kPlaceStretch, threads);
}

CellPlaceEnergy cell_place_energy(const synth::TextureMap& map, uint64_t seed,
                                  const TextureEnergy& energy, size_t samples, int threads) {
    return cell_place_energy(cell_place_plane(map, seed, threads),
                             {map.cell_width, map.cell_height}, energy, samples, seed);
}

}  // namespace tilejet::quality
