#include <catch2/catch.hpp>
#include <set>

#include "tilejet/synth/tile_region.hpp"

using namespace tilejet::synth;

TEST_CASE("scatter tiles are far apart and inside the plane", "[tiles]") {
    const TileGeometry g{1200, 600, TileLayout::Scatter, 10};
    std::set<std::pair<int64_t, int64_t>> seen;
    for (uint64_t k = 0; k < 2000; ++k) {
        const Region r = tile_region(77, k, g);
        REQUIRE(r.width == 1200);
        REQUIRE(r.height == 600);
        REQUIRE(r.x >= -(int64_t(1) << 31));
        REQUIRE(r.x + r.width <= int64_t(1) << 31);
        REQUIRE(r.y >= -(int64_t(1) << 31));
        REQUIRE(r.y + r.height <= int64_t(1) << 31);
        seen.insert({r.x / 4096, r.y / 4096});
    }
    REQUIRE(seen.size() == 2000);  // no two tiles anywhere near each other
}

TEST_CASE("tile positions depend only on seed, index and geometry", "[tiles]") {
    const TileGeometry g{800, 800, TileLayout::Scatter, 10};
    const Region a = tile_region(5, 41237, g), b = tile_region(5, 41237, g);
    REQUIRE((a.x == b.x && a.y == b.y));
    const Region c = tile_region(6, 41237, g);
    REQUIRE((a.x != c.x || a.y != c.y));
}

TEST_CASE("wall tiles join edge to edge, row by row", "[tiles]") {
    const TileGeometry g{300, 200, TileLayout::Wall, 4};
    const Region t0 = tile_region(9, 0, g), t1 = tile_region(9, 1, g), t3 = tile_region(9, 3, g);
    const Region t4 = tile_region(9, 4, g), t9 = tile_region(9, 9, g);
    REQUIRE(t1.x == t0.x + 300);
    REQUIRE(t1.y == t0.y);
    REQUIRE(t3.x == t0.x + 900);
    REQUIRE(t4.x == t0.x);
    REQUIRE(t4.y == t0.y + 200);
    REQUIRE(t9.x == t0.x + 300);
    REQUIRE(t9.y == t0.y + 400);
}

TEST_CASE("layout names parse", "[tiles]") {
    REQUIRE(parse_tile_layout("scatter") == TileLayout::Scatter);
    REQUIRE(parse_tile_layout("wall") == TileLayout::Wall);
    REQUIRE_FALSE(parse_tile_layout("grid").has_value());
}
