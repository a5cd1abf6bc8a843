#pragma once

// Where tile k of a job lies on the texture plane (docs/design.md section 3.6, "Tile regions").

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "tilejet/synth/sampler.hpp"

namespace tilejet::synth {

enum class TileLayout {
    Scatter,  // every tile far from every other: no two tiles of a run share texture
    Wall,     // tiles laid row by row on a wall W tiles wide, veins continuing across joints
};

std::optional<TileLayout> parse_tile_layout(std::string_view name);
std::string_view tile_layout_name(TileLayout layout);
// The layouts' names as an error message lists them ("scatter or wall").
std::string tile_layout_choices();

struct TileGeometry {
    int width = 0, height = 0;  // pixels
    TileLayout layout = TileLayout::Scatter;
    int wall_width = 10;  // tiles per wall row, for TileLayout::Wall
};

// Tile `index` of a job with `seed`. Depends only on (seed, index, geometry).
Region tile_region(uint64_t seed, uint64_t index, const TileGeometry& geometry);

}  // namespace tilejet::synth
