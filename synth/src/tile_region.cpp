#include "tilejet/synth/tile_region.hpp"

#include "tilejet/config/enum_names.hpp"
#include "tilejet/synth/internal/mix64.hpp"

namespace tilejet::synth {

namespace {

constexpr config::EnumNames kLayouts{std::array<std::pair<TileLayout, std::string_view>, 2>{{
    {TileLayout::Scatter, "scatter"},
    {TileLayout::Wall, "wall"},
}}};

}  // namespace

std::optional<TileLayout> parse_tile_layout(std::string_view name) {
    return kLayouts.parse(name);
}

std::string_view tile_layout_name(TileLayout layout) {
    return kLayouts.name(layout);
}

std::string tile_layout_choices() {
    return kLayouts.choices();
}

Region tile_region(uint64_t seed, uint64_t index, const TileGeometry& g) {
    using detail::hash_combine;
    // Origins stay within +-2^30 so that a tile of any practical size lies inside +-2^31.
    constexpr int64_t kHalfRange = int64_t(1) << 30;
    if (g.layout == TileLayout::Scatter) {
        // Two tiles of a run are ~2^30 px apart on average: they never share a cell.
        const uint64_t h = hash_combine(hash_combine(seed, 0x5c477e5ull), index);
        return {int64_t(h >> 33) - kHalfRange, int64_t(h & 0x7fffffffull) - kHalfRange, g.width,
                g.height};
    }
    const uint64_t h = hash_combine(seed, 0x3a11ull);
    const int64_t wall_x = int64_t(h >> 35) - (kHalfRange >> 1);
    const int64_t wall_y = int64_t(h & 0x1fffffffull) - (kHalfRange >> 1);
    const uint64_t per_row = uint64_t(g.wall_width > 0 ? g.wall_width : 1);
    return {wall_x + int64_t(index % per_row) * g.width,
            wall_y + int64_t(index / per_row) * g.height, g.width, g.height};
}

}  // namespace tilejet::synth
