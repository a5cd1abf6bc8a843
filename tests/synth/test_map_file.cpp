// The texture map file: round trip, and every kind of damage gives a clear error.

#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <cstring>
#include <fstream>
#include <opencv2/core.hpp>

#include "cell_image_coding.hpp"
#include "fixtures.hpp"
#include "tilejet/synth/map_file.hpp"
#include "tilejet/synth/sampler.hpp"

using namespace tilejet::synth;
using Catch::Matchers::Contains;
using tilejet::test::small_map;
using tilejet::test::TempDir;

namespace {

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

uint64_t get_le(const std::string& bytes, size_t at, int n) {
    uint64_t v = 0;
    for (int i = 0; i < n; ++i)
        v |= uint64_t(uint8_t(bytes[at + size_t(i)])) << (8 * i);
    return v;
}

void put_le(std::string& out, uint64_t v, int n) {
    for (int i = 0; i < n; ++i)
        out += char(v >> (8 * i));
}

uint32_t crc32_of(const std::string& bytes) {  // the map format's CRC-32 (zlib's polynomial)
    uint32_t c = 0xffffffffu;
    for (char ch : bytes) {
        c ^= uint8_t(ch);
        for (int k = 0; k < 8; ++k)
            c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
    }
    return ~c;
}

// A section as the container holds it: payload as stored, its raw length and flags.
struct StoredSection {
    std::string tag;
    uint32_t index, raw_len, flags;
    std::string payload;
};

// The sections of a map file, read by the file layout (map_file.cpp), and a file made of any
// sections with a correct header, table and checksums: what a crafted file looks like.
std::vector<StoredSection> sections_of(const std::string& file) {
    const uint32_t count = uint32_t(get_le(file, 12, 4));
    std::vector<StoredSection> out;
    for (uint32_t s = 0; s < count; ++s) {
        const size_t e = 32 + 32 * size_t(s);
        const uint64_t offset = get_le(file, e + 8, 8), stored = get_le(file, e + 16, 4);
        out.push_back({file.substr(e, 4), uint32_t(get_le(file, e + 4, 4)),
                       uint32_t(get_le(file, e + 20, 4)), uint32_t(get_le(file, e + 28, 4)),
                       file.substr(size_t(offset), size_t(stored))});
    }
    return out;
}

// `version`: what maps of one cell image, the ones these tests craft, are written with.
std::string file_of(const std::vector<StoredSection>& sections, uint32_t version = 2) {
    std::string table, payloads;
    uint64_t offset = 32 + 32 * sections.size();
    for (const StoredSection& s : sections) {
        table += s.tag;
        put_le(table, s.index, 4), put_le(table, offset, 8), put_le(table, s.payload.size(), 4);
        put_le(table, s.raw_len, 4), put_le(table, crc32_of(s.payload), 4);
        put_le(table, s.flags, 4);
        payloads += s.payload;
        offset += s.payload.size();
    }
    std::string out = "TJMAP\r\n\x1a";
    put_le(out, version, 4), put_le(out, sections.size(), 4), put_le(out, offset, 8);
    put_le(out, crc32_of(table), 4), put_le(out, 0, 4);
    return out + table + payloads;
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
    REQUIRE(cv::norm(a.pixels, b.pixels, cv::NORM_INF) == 0);
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
    REQUIRE(tilejet::test::read_file(dir / "m.tjmap") ==
            tilejet::test::read_file(dir / "again.tjmap"));
}

TEST_CASE("damaged map files are refused with a message naming the file", "[mapfile]") {
    TempDir dir;
    save_texture_map(small_map(), dir / "good.tjmap");
    const std::string good = tilejet::test::read_file(dir / "good.tjmap");
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
    SECTION("the container rebuilt by the test is itself a good map") {
        REQUIRE(file_of(sections_of(good)) == good);
    }
    SECTION("a section the format does not know, however valid, is refused before it inflates") {
        auto sections = sections_of(good);
        // Claims 256 MiB inflated: refused from the table, before any allocation.
        sections.insert(sections.begin() + 1, {"JUNK", 0, 256u << 20, 1, "x"});
        REQUIRE_THAT(load_error(dir, file_of(sections)),
                     Contains(name) && Contains("JUNK[0] is not a section of a texture map"));
    }
    SECTION("sections that would inflate past what a map can be are refused before inflating") {
        auto sections = sections_of(good);
        for (uint32_t i = 100; i < 105; ++i)
            sections.push_back({"CELL", i, 250u << 20, 1, "x"});
        REQUIRE_THAT(load_error(dir, file_of(sections)), Contains(name) && Contains("inflate"));
    }
    SECTION("a known section the map does not use is refused") {
        auto sections = sections_of(good);
        sections.push_back({"CELL", 7, 1, 0, "x"});
        REQUIRE_THAT(load_error(dir, file_of(sections)),
                     Contains(name) && Contains("CELL[7] is not part of this map"));
    }
    SECTION("a known section no map of this many cell images uses is refused before inflating") {
        auto sections = sections_of(good);
        // Claims 200 MiB inflated (and would not inflate at all): the table and META alone
        // refuse it, so no decompression is tried.
        sections.push_back({"OVLA", 9, 200u << 20, 1, "x"});
        REQUIRE_THAT(load_error(dir, file_of(sections)),
                     Contains(name) && Contains("OVLA[9] is not part of this map"));
        sections.back() = {"SRCE", 1, 200u << 20, 1, "x"};
        REQUIRE_THAT(load_error(dir, file_of(sections)),
                     Contains(name) && Contains("SRCE[1] is not part of this map"));
    }
    SECTION("a patch count the section cannot hold is refused before the patches are allocated") {
        auto sections = sections_of(good);
        for (StoredSection& sec : sections)
            if (sec.tag == "PATA" && sec.index == 0) {
                sec.payload.clear();
                put_le(sec.payload, 65535, 4), put_le(sec.payload, 0, 8);
                sec.raw_len = uint32_t(sec.payload.size()), sec.flags = 0;
            }
        REQUIRE_THAT(load_error(dir, file_of(sections)),
                     Contains("PATA[0]") && Contains("ends before its 65535 patches"));
    }
    SECTION("a variant rule on a set of one variant is refused, naming CSET") {
        // What no tilejet writes (the rule is kept only with two variants): a version 3 file
        // whose META counts the 16 images of one variant and whose CSET is K 2, V 1, rule 1.
        // CSET is checked before any cell image is read.
        const TextureMap& map = small_map();
        std::string meta, cset;
        put_le(meta, uint32_t(map.cell_width), 4), put_le(meta, uint32_t(map.cell_height), 4);
        put_le(meta, 16, 4), put_le(meta, map.build.seed, 8);
        for (int field = 0; field < 4; ++field)
            put_le(meta, 64, 4);
        put_le(meta, 0x4010000000000000ull, 8);  // 4.0 active patches per cell
        put_le(cset, 2, 4), put_le(cset, 1, 4), put_le(cset, 1, 4);
        auto sections = sections_of(good);
        for (StoredSection& sec : sections)
            if (sec.tag == "META") sec = {"META", 0, uint32_t(meta.size()), 0, meta};
        sections.insert(sections.begin() + 1, {"CSET", 0, uint32_t(cset.size()), 0, cset});
        REQUIRE_THAT(load_error(dir, file_of(sections, 3)),
                     Contains(name) && Contains("CSET") &&
                         Contains("variant rule 1 needs 2 variants, the map has 1"));
        // The same file with two variants' worth of rule accepted as far as CSET: it then
        // misses its other cell images, which shows the refusal above was the rule's.
        std::string two = cset;
        put_u32(two, 4, 2);
        for (StoredSection& sec : sections)
            if (sec.tag == "CSET") sec.payload = two;
        REQUIRE_THAT(load_error(dir, file_of(sections, 3)),
                     Contains("need 32 cell images, the map holds 16"));
    }
    SECTION("a section twice is refused") {
        auto sections = sections_of(good);
        sections.push_back(sections.front());
        REQUIRE_THAT(load_error(dir, file_of(sections)), Contains("appears twice"));
    }
    SECTION("only regular files are read: no FIFO, device or directory") {
        const auto fifo = dir / "fifo.tjmap";
        REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
        for (const std::filesystem::path& p :
             {fifo, std::filesystem::path("/dev/zero"), std::filesystem::path(dir.path())})
            REQUIRE_THROWS_WITH(load_texture_map(p),
                                Contains(p.string()) && Contains("not a regular file"));
    }
    SECTION("empty and missing files") {
        REQUIRE_THAT(load_error(dir, ""), Contains(name) && Contains("empty"));
        REQUIRE_THROWS_WITH(load_texture_map(dir / "nope.tjmap"),
                            Contains("nope.tjmap") && Contains("No such file"));
    }
}

TEST_CASE("damaged cell images coded against the source are refused, naming the section",
          "[mapfile][coding]") {
    TempDir dir;
    TextureMap map = small_map();
    map.cell_storage = TextureMap::CellStorage::against_source;
    save_texture_map(map, dir / "coded.tjmap");
    const std::string good = tilejet::test::read_file(dir / "coded.tjmap");
    REQUIRE(load_error(dir, good).empty());
    const auto flag = [&](const std::string& tag, uint32_t flags, uint32_t version) {
        auto sections = sections_of(good);
        for (StoredSection& sec : sections)
            if (sec.tag == tag) sec.flags = flags;
        return load_error(dir, file_of(sections, version));
    };
    REQUIRE(flag("CELL", 3, 4).empty());  // the file as written, rebuilt by the test
    SECTION("the coded flag on a section other than a cell image") {
        REQUIRE_THAT(flag("SRCE", 3, 4), Contains("SRCE[0]") && Contains("only cell images are"));
    }
    SECTION("a coded cell image in a file of a version before coding") {
        REQUIRE_THAT(flag("CELL", 3, 3),
                     Contains("CELL[0]") && Contains("format version 3 (it came with version 4)"));
    }
    SECTION("flags this tilejet does not know") {
        REQUIRE_THAT(flag("CELL", 3 | 8, 4), Contains("CELL[0] has unknown flags 11"));
    }
    SECTION("a cell image coded, but the flag not set: its bytes are no image") {
        REQUIRE_THAT(flag("CELL", 1, 4), Contains("CELL[0]"));
    }
    SECTION("a block copying from outside the source, stored uncompressed") {
        std::vector<uint8_t> coded = tilejet::synth::detail::code_cell_images(
                                         std::vector{map.cell_images[0].pixels}, map.source)
                                         .front();
        coded[8] = 0xff, coded[9] = 0x7f;  // the first block's dx: 32767 px
        auto sections = sections_of(good);
        for (StoredSection& sec : sections)
            if (sec.tag == "CELL")
                sec = {"CELL", 0, uint32_t(coded.size()), 2,
                       std::string(coded.begin(), coded.end())};
        REQUIRE_THAT(load_error(dir, file_of(sections, 4)),
                     Contains(dir.path().string()) && Contains("CELL[0]") &&
                         Contains("block 0,0 copies from outside the source"));
    }
}
