// The texture map file: round trip, and every kind of damage gives a clear error.

#include <catch2/catch.hpp>
#include <cstring>
#include <fstream>
#include <opencv2/core.hpp>

#include "fixtures.hpp"
#include "tilejet/synth/map_file.hpp"
#include "tilejet/synth/sampler.hpp"

using namespace tilejet::synth;
using Catch::Matchers::Contains;
using tilejet::test::small_map;
using tilejet::test::TempDir;

namespace {

std::string read_all(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The error message loading `bytes` from a file gives, or "" when it loads.
std::string load_error(const TempDir& dir, const std::string& bytes) {
    const auto path = dir / "damaged.tjmap";
    tilejet::test::write_file(path, bytes);
    try {
        load_texture_map(path);
    } catch (const MapFileError& e) {
        return e.what();
    }
    return "";
}

void put_u32(std::string& bytes, size_t at, uint32_t v) {
    for (int i = 0; i < 4; ++i)
        bytes[at + size_t(i)] = char(v >> (8 * i));
}

}  // namespace

TEST_CASE("a texture map survives saving and loading unchanged", "[mapfile]") {
    TempDir dir;
    const TextureMap& map = small_map();
    save_texture_map(map, dir / "m.tjmap");
    const TextureMap back = load_texture_map(dir / "m.tjmap");

    REQUIRE(back.id == map.id);
    REQUIRE(back.cell_width == map.cell_width);
    REQUIRE(back.cell_height == map.cell_height);
    REQUIRE(back.build.seed == map.build.seed);
    REQUIRE(cv::norm(back.source, map.source, cv::NORM_INF) == 0);
    const CellImage &a = map.cell_images.front(), &b = back.cell_images.front();
    REQUIRE(cv::norm(a.rgb, b.rgb, cv::NORM_INF) == 0);
    for (CellType t : {CellType::A, CellType::B}) {
        const PatchSet &sa = a.set(t), &sb = b.set(t);
        REQUIRE(sa.size() == sb.size());
        REQUIRE(sa.activation_threshold == sb.activation_threshold);
        REQUIRE(sa.overlap_bits == sb.overlap_bits);
        for (size_t k = 0; k < sa.size(); ++k) {
            REQUIRE(sa.patches[k].bits == sb.patches[k].bits);
            REQUIRE(sa.patches[k].x == sb.patches[k].x);
            REQUIRE(sa.patches[k].src_y == sb.patches[k].src_y);
        }
    }
    const Region region{-1000, 5000, 300, 200};
    REQUIRE(cv::norm(render_region(map, 5, region), render_region(back, 5, region), cv::NORM_INF) ==
            0);
    // Saving is deterministic: the same map gives the same bytes.
    save_texture_map(back, dir / "again.tjmap");
    REQUIRE(read_all(dir / "m.tjmap") == read_all(dir / "again.tjmap"));
}

TEST_CASE("damaged map files are refused with a message naming the file", "[mapfile]") {
    TempDir dir;
    save_texture_map(small_map(), dir / "good.tjmap");
    const std::string good = read_all(dir / "good.tjmap");
    const std::string name = (dir / "damaged.tjmap").string();
    REQUIRE(load_error(dir, good).empty());

    SECTION("truncated") {
        for (size_t keep : {good.size() - 1, good.size() / 2, size_t(40), size_t(10)}) {
            const std::string e = load_error(dir, good.substr(0, keep));
            REQUIRE_THAT(e, Contains(name));
            REQUIRE_THAT(e, Contains("truncated") || Contains("ends before"));
        }
    }
    SECTION("a flipped byte anywhere") {
        for (size_t at = 0; at < good.size(); at += 61) {
            std::string bad = good;
            bad[at] = char(bad[at] ^ 0x20);
            const std::string e = load_error(dir, bad);
            INFO("flipped byte " << at);
            REQUIRE_THAT(e, Contains(name));
        }
    }
    SECTION("a flipped byte in a section payload is a checksum error") {
        std::string bad = good;
        bad[good.size() - 40] = char(bad[good.size() - 40] ^ 1);
        REQUIRE_THAT(load_error(dir, bad), Contains("corrupted"));
    }
    SECTION("wrong magic") {
        std::string bad = good;
        bad[1] = 'X';
        REQUIRE_THAT(load_error(dir, bad), Contains(name) && Contains("not a tilejet texture map"));
        REQUIRE_THAT(load_error(dir, "\x89PNG\r\n\x1a\n and then some"), Contains("wrong magic"));
    }
    SECTION("a newer format version") {
        std::string bad = good;
        put_u32(bad, 8, kMapFormatVersion + 1);
        REQUIRE_THAT(load_error(dir, bad), Contains(name) && Contains("newer"));
    }
    SECTION("trailing garbage") {
        REQUIRE_THAT(load_error(dir, good + "xyz"), Contains(name) && Contains("trailing"));
    }
    SECTION("empty and missing files") {
        REQUIRE_THAT(load_error(dir, ""), Contains(name) && Contains("empty"));
        REQUIRE_THROWS_WITH(load_texture_map(dir / "nope.tjmap"),
                            Contains("nope.tjmap") && Contains("No such file"));
    }
}
