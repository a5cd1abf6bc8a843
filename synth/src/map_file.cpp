#include "tilejet/synth/map_file.hpp"

#include <fcntl.h>
#include <openssl/evp.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>

#include "cell_image_coding.hpp"
#include "map_bytes.hpp"
#include "tilejet/synth/exemplar.hpp"
#include "tilejet/synth/internal/corner_colours.hpp"
#include "tilejet/synth/internal/diamond.hpp"

namespace tilejet::synth {

namespace {

using detail::Reader;
using detail::Writer;

// File layout (all integers little-endian):
//   header  : magic[8] "TJMAP\r\n\x1a", u32 version, u32 section count, u64 file length,
//             u32 CRC-32 of the section table, u32 reserved (0)
//   table   : per section: tag[4], u32 index, u64 offset, u32 stored length, u32 raw length,
//             u32 CRC-32 of the stored bytes, u32 flags (bit 0: zlib-compressed; bit 1: a CELL
//             section coded against the source, cell_image_coding.hpp, version 4 on)
//   payloads: back to back.
// The magic's CR LF and ^Z catch text-mode transfers, as PNG's does.
constexpr char kMagic[8] = {'T', 'J', 'M', 'A', 'P', '\r', '\n', '\x1a'};
constexpr size_t kHeaderBytes = 32, kEntryBytes = 32;
constexpr uint32_t kFlagZlib = 1, kFlagSourceCoded = 2;
constexpr uint32_t kSourceCodedVersion = 4;
constexpr uint32_t kMaxSections = 4096;
// META holds a few numbers.
constexpr uint32_t kMaxMetaBytes = 1024;
constexpr uint32_t kMaxRawSection = 256u << 20;
// A whole map, on disk and inflated: a 8192 px slab's source is 201 MB raw.
constexpr uint64_t kMaxFileBytes = uint64_t(1) << 30, kMaxRawTotal = uint64_t(1) << 30;
// The sections a map is made of; any other is refused (a file of unknown sections that
// inflate to 256 MiB each, with valid checksums and id, cost every load 2 GB).
constexpr std::array<std::string_view, 10> kKnownTags = {"META", "CSET", "PHYS", "SRCE", "CELL",
                                                         "PATA", "PATB", "OVLA", "OVLB", "IDNT"};
// PHYS: print and exemplar resolutions (kMinDpi..kMaxDpi), the grain the cell came from (px).
constexpr int kMaxCellSide = 8192, kMaxSourceSide = 16384;
constexpr int kMaxCornerColours = 4;
constexpr int kMaxVariants = 2;  // the (i + j) mod 2 rule of corner_colours.hpp
// With VariantRule::plain_in_four, plain combinations' variants 2 and 3 besides.
constexpr uint32_t kMaxCellImages =
    kMaxCornerColours * kMaxCornerColours * kMaxCornerColours * kMaxCornerColours * kMaxVariants +
    kMaxCornerColours * (detail::kPlainVariants - kMaxVariants);

// Fuzzing builds skip the checksums and the id check, so that mutated files reach the parser and
// the checks behind it (patch bounds, diamonds) instead of stopping at the first CRC.
#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
constexpr bool kVerifyChecksums = false;
#else
constexpr bool kVerifyChecksums = true;
#endif

struct Section {
    std::string tag;  // four characters
    uint32_t index = 0;
    std::vector<uint8_t> raw;
};

uint32_t crc_of(std::span<const uint8_t> b) {
    uLong crc = crc32(0L, Z_NULL, 0);
    // zlib takes uInt lengths; sections are far below 4 GiB.
    return uint32_t(crc32(crc, b.data(), uInt(b.size())));
}

void write_image(Writer& w, const cv::Mat& rgb) {
    w.le<uint32_t>(uint32_t(rgb.cols));
    w.le<uint32_t>(uint32_t(rgb.rows));
    for (int r = 0; r < rgb.rows; ++r)
        w.u8s(rgb.ptr(r), size_t(rgb.cols) * 3);
}

cv::Mat read_image(Reader& r, int max_side) {
    const auto w = r.le<uint32_t>("image width"), h = r.le<uint32_t>("image height");
    if (w == 0 || h == 0 || w > uint32_t(max_side) || h > uint32_t(max_side))
        r.fail("image size " + std::to_string(w) + "x" + std::to_string(h) + " is out of range");
    auto px = r.take(size_t(w) * h * 3, "image pixels");
    cv::Mat rgb(int(h), int(w), CV_8UC3);
    std::memcpy(rgb.data, px.data(), px.size());
    return rgb;
}

void write_patches(Writer& w, const PatchSet& set) {
    w.le<uint32_t>(uint32_t(set.size()));
    w.le<uint64_t>(set.activation_threshold);
    for (const Patch& p : set.patches) {
        w.le<int32_t>(p.x), w.le<int32_t>(p.y);
        w.le<uint32_t>(uint32_t(p.width)), w.le<uint32_t>(uint32_t(p.height));
        w.le<int32_t>(p.src_x), w.le<int32_t>(p.src_y);
        w.f32(p.seam_cost);
        w.u8s(p.bits.data(), p.bits.size());
    }
}

bool runs_inside_diamond(const Patch& p, const detail::CellGrid& grid) {
    // Diamonds are convex: a run is inside when both its ends are.
    for (const MaskRun& run : p.runs) {
        const int64_t y = p.y + run.row, xa = p.x + run.x, xb = p.x + run.x + run.length - 1;
        if (!grid.in_diamond_interior(xa, y) || !grid.in_diamond_interior(xb, y)) return false;
    }
    return true;
}

bool runs_inside_cell(const Patch& p, int width, int height) {
    for (const MaskRun& run : p.runs) {
        const int64_t y = int64_t(p.y) + run.row, xa = int64_t(p.x) + run.x,
                      xb = xa + run.length - 1;
        if (y < 0 || y >= height || xa < 0 || xb >= width) return false;
    }
    return true;
}

PatchSet read_patches(Reader& r, const TextureMap& map) {
    PatchSet set;
    const auto n = r.le<uint32_t>("patch count");
    if (n > 65535) r.fail("patch count " + std::to_string(n) + " is over 65535");
    set.activation_threshold = r.le<uint64_t>("activation threshold");
    // Each patch takes 28 bytes before its mask: a count the section cannot hold is refused
    // before the patches are allocated.
    if (r.remaining() < size_t(n) * 28) r.fail("ends before its " + std::to_string(n) + " patches");
    const detail::CellGrid grid(map.cell_width, map.cell_height);
    set.patches.resize(n);
    for (uint32_t k = 0; k < n; ++k) {
        Patch& p = set.patches[k];
        p.x = r.le<int32_t>("patch x"), p.y = r.le<int32_t>("patch y");
        const auto w = r.le<uint32_t>("patch width"), h = r.le<uint32_t>("patch height");
        p.src_x = r.le<int32_t>("patch source x"), p.src_y = r.le<int32_t>("patch source y");
        p.seam_cost = r.f32("patch seam cost");
        const std::string which = "patch " + std::to_string(k);
        if (w == 0 || h == 0 || w > uint32_t(2 * map.cell_width) ||
            h > uint32_t(2 * map.cell_height))
            r.fail(which + " has size " + std::to_string(w) + "x" + std::to_string(h));
        p.width = int(w), p.height = int(h);
        if (p.src_x < 0 || p.src_y < 0 || int64_t(p.src_x) + p.width > map.source.cols ||
            int64_t(p.src_y) + p.height > map.source.rows)
            r.fail(which + " copies from outside the source image");
        auto bits = r.take(size_t(p.height) * size_t(p.row_bytes()), "patch mask");
        p.bits.assign(bits.begin(), bits.end());
        p.derive_runs();
        if (!runs_inside_diamond(p, grid)) r.fail(which + " leaves its cell's diamond");
        // A set's patches stay in their own cell (cell_set.hpp): one over a neighbour, whose
        // image has other patches, would make sampling and region rendering disagree.
        if (map.corner_colours > 1 && !runs_inside_cell(p, map.cell_width, map.cell_height))
            r.fail(which + " of a cell set leaves its cell");
    }
    return set;
}

void write_overlaps(Writer& w, const PatchSet& set) {
    w.le<uint32_t>(uint32_t(set.size()));
    for (uint64_t word : set.overlap_bits)
        w.le<uint64_t>(word);
}

void read_overlaps(Reader& r, PatchSet& set) {
    const auto n = r.le<uint32_t>("overlap matrix size");
    if (n != set.size())
        r.fail("overlap matrix is for " + std::to_string(n) + " patches, the set has " +
               std::to_string(set.size()));
    // Checked against what the section holds before the matrix is allocated.
    const size_t words = set.size() * set.overlap_row_words();
    if (r.remaining() != words * sizeof(uint64_t))
        r.fail("overlap matrix of " + std::to_string(n) + " patches needs " +
               std::to_string(words * sizeof(uint64_t)) + " bytes, the section holds " +
               std::to_string(r.remaining()));
    set.overlap_bits.resize(words);
    for (uint64_t& word : set.overlap_bits)
        word = r.le<uint64_t>("overlap bits");
}

// Only a set of two variants that does not show them by parity records its rule (version 3;
// the hashed and plain-in-four rules came later in the same version: older readers refuse them by
// name).
bool records_variant_rule(const TextureMap& map) {
    return map.variants > 1 && map.variant_rule != TextureMap::VariantRule::parity;
}

std::vector<Section> content_sections(const TextureMap& map) {
    std::vector<Section> out;
    {
        Writer w;
        w.le<uint32_t>(uint32_t(map.cell_width)), w.le<uint32_t>(uint32_t(map.cell_height));
        w.le<uint32_t>(uint32_t(map.cell_images.size()));
        w.le<uint64_t>(map.build.seed);
        w.le<uint32_t>(uint32_t(map.build.exemplar_width));
        w.le<uint32_t>(uint32_t(map.build.exemplar_height));
        w.le<uint32_t>(uint32_t(map.build.patches_requested));
        w.le<uint32_t>(uint32_t(map.build.candidates));
        w.f64(map.build.active_per_cell);
        out.push_back({"META", 0, std::move(w.bytes)});
    }
    // Only sets carry it, so that maps of one cell image keep the content, and so the id, that
    // they had before cell sets.
    if (map.corner_colours > 1) {
        Writer w;
        w.le<uint32_t>(uint32_t(map.corner_colours));
        // Only sets of variants carry it, so that sets of one image per combination keep their id.
        if (map.variants > 1) w.le<uint32_t>(uint32_t(map.variants));
        // Likewise only sets whose variants break twins (hashed or not): parity maps keep
        // their id.
        if (records_variant_rule(map)) w.le<uint32_t>(uint32_t(map.variant_rule));
        out.push_back({"CSET", 0, std::move(w.bytes)});
    }
    // Likewise only maps that know their size: the id of a map built without stays what it was.
    if (map.build.dpi > 0) {
        Writer w;
        w.f64(map.build.dpi);
        w.f64(map.build.exemplar_dpi);
        w.f64(map.build.grain);
        out.push_back({"PHYS", 0, std::move(w.bytes)});
    }
    {
        Writer w;
        write_image(w, map.source);
        out.push_back({"SRCE", 0, std::move(w.bytes)});
    }
    for (size_t t = 0; t < map.cell_images.size(); ++t) {
        const CellImage& c = map.cell_images[t];
        Writer img, pa, pb, oa, ob;
        write_image(img, c.pixels);
        write_patches(pa, c.a), write_patches(pb, c.b);
        write_overlaps(oa, c.a), write_overlaps(ob, c.b);
        out.push_back({"CELL", uint32_t(t), std::move(img.bytes)});
        out.push_back({"PATA", uint32_t(t), std::move(pa.bytes)});
        out.push_back({"PATB", uint32_t(t), std::move(pb.bytes)});
        out.push_back({"OVLA", uint32_t(t), std::move(oa.bytes)});
        out.push_back({"OVLB", uint32_t(t), std::move(ob.bytes)});
    }
    return out;
}

std::array<uint8_t, 32> content_hash(const std::vector<Section>& sections) {
    std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(), EVP_MD_CTX_free);
    if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) != 1)
        throw SynthError("OpenSSL SHA-256 is unavailable");
    for (const Section& s : sections) {
        Writer w;
        w.u8s(s.tag.data(), 4);
        w.le<uint32_t>(s.index);
        w.le<uint64_t>(s.raw.size());
        EVP_DigestUpdate(ctx.get(), w.bytes.data(), w.bytes.size());
        EVP_DigestUpdate(ctx.get(), s.raw.data(), s.raw.size());
    }
    std::array<uint8_t, 32> out{};
    unsigned int len = 0;
    EVP_DigestFinal_ex(ctx.get(), out.data(), &len);
    return out;
}

std::vector<uint8_t> deflate_bytes(const std::vector<uint8_t>& raw) {
    uLongf len = compressBound(uLong(raw.size()));
    std::vector<uint8_t> out(len);
    if (compress2(out.data(), &len, raw.data(), uLong(raw.size()), 6) != Z_OK)
        throw SynthError("zlib could not compress a map section");
    out.resize(len);
    return out;
}

}  // namespace

void assign_map_id(TextureMap& map) {
    map.id = content_hash(content_sections(map));
}

uint32_t format_version_of(const TextureMap& map) {
    if (map.cell_storage == TextureMap::CellStorage::against_source) return kSourceCodedVersion;
    return records_variant_rule(map) ? 3 : 2;
}

std::vector<uint8_t> encode_texture_map(const TextureMap& map) {
    std::vector<Section> sections = content_sections(map);
    sections.push_back({"IDNT", 0, std::vector<uint8_t>(map.id.begin(), map.id.end())});
    // The id above is that of the pixels; the file may keep them coded.
    std::vector<uint32_t> flags(sections.size(), kFlagZlib);
    if (map.cell_storage == TextureMap::CellStorage::against_source &&
        map.source.type() == CV_8UC3) {
        std::vector<cv::Mat> cells;
        for (const CellImage& c : map.cell_images)
            cells.push_back(c.pixels);
        std::vector<std::vector<uint8_t>> coded = detail::code_cell_images(cells, map.source);
        for (size_t i = 0; i < sections.size(); ++i)
            if (sections[i].tag == "CELL") {
                sections[i].raw = std::move(coded[sections[i].index]);
                flags[i] |= kFlagSourceCoded;
            }
    }

    std::vector<std::vector<uint8_t>> stored;
    for (const Section& s : sections)
        stored.push_back(deflate_bytes(s.raw));

    Writer table;
    uint64_t offset = kHeaderBytes + kEntryBytes * sections.size();
    for (size_t i = 0; i < sections.size(); ++i) {
        table.u8s(sections[i].tag.data(), 4);
        table.le<uint32_t>(sections[i].index);
        table.le<uint64_t>(offset);
        table.le<uint32_t>(uint32_t(stored[i].size()));
        table.le<uint32_t>(uint32_t(sections[i].raw.size()));
        table.le<uint32_t>(crc_of(stored[i]));
        table.le<uint32_t>(flags[i]);
        offset += stored[i].size();
    }
    Writer out;
    out.u8s(kMagic, sizeof kMagic);
    out.le<uint32_t>(format_version_of(map));
    out.le<uint32_t>(uint32_t(sections.size()));
    out.le<uint64_t>(offset);
    out.le<uint32_t>(crc_of(table.bytes));
    out.le<uint32_t>(0);
    out.u8s(table.bytes.data(), table.bytes.size());
    for (const auto& s : stored)
        out.u8s(s.data(), s.size());
    return std::move(out.bytes);
}

TextureMap decode_texture_map(std::span<const uint8_t> bytes, const std::string& name) {
    const std::string where = "texture map '" + name + "'";
    const Reader whole(bytes, where);
    auto fail = [&](const std::string& why) { whole.fail(why); };

    if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
        fail("not a tilejet texture map (wrong magic)");
    Reader header(bytes.first(std::min(bytes.size(), kHeaderBytes)), where + " header");
    header.take(sizeof kMagic, "magic");
    const auto version = header.le<uint32_t>("format version");
    if (version > kMapFormatVersion)
        fail("format version " + std::to_string(version) + " is newer than this tilejet reads (" +
             std::to_string(kMapFormatVersion) + "); update tilejet or rebuild the map");
    if (version == 0) fail("format version 0 is invalid");
    const auto count = header.le<uint32_t>("section count");
    const auto length = header.le<uint64_t>("file length");
    const auto table_crc = header.le<uint32_t>("section table checksum");
    if (length != bytes.size())
        fail(length > bytes.size()
                 ? "truncated: " + std::to_string(bytes.size()) + " of " + std::to_string(length) +
                       " bytes present"
                 : std::to_string(bytes.size() - length) + " bytes of trailing data after the map");
    if (count == 0 || count > kMaxSections)
        fail("section count " + std::to_string(count) + " is invalid");
    if (bytes.size() < kHeaderBytes + size_t(count) * kEntryBytes) fail("truncated section table");
    auto table_bytes = bytes.subspan(kHeaderBytes, size_t(count) * kEntryBytes);
    if (crc_of(table_bytes) != table_crc && kVerifyChecksums)
        fail("section table is corrupted (checksum mismatch)");

    // First the table alone: every section known, inside the file, once, and all of them
    // together no larger than a map can be, before anything is inflated.
    struct Entry {
        std::string tag;
        uint32_t index;
        std::span<const uint8_t> payload;
        uint32_t raw_len, crc, flags;
        std::string label;
    };
    std::vector<Entry> entries;
    std::map<std::pair<std::string, uint32_t>, size_t> where_is;
    // What the sections inflate to (and coded cell images decode to), all together.
    uint64_t raw_total = 0;
    const auto count_raw = [&](uint64_t bytes_more) {
        raw_total += bytes_more;
        if (raw_total > kMaxRawTotal)
            fail("sections inflate to over " + std::to_string(kMaxRawTotal >> 20) + " MiB");
    };
    Reader table(table_bytes, where + " section table");
    for (uint32_t s = 0; s < count; ++s) {
        auto tag_bytes = table.take(4, "section tag");
        Entry e;
        e.tag.assign(tag_bytes.begin(), tag_bytes.end());
        e.index = table.le<uint32_t>("section index");
        const auto offset = table.le<uint64_t>("section offset");
        const auto stored = table.le<uint32_t>("section length");
        e.raw_len = table.le<uint32_t>("section raw length");
        e.crc = table.le<uint32_t>("section checksum");
        e.flags = table.le<uint32_t>("section flags");
        std::string printable;
        for (char c : e.tag)
            printable += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
        e.label = "section " + printable + "[" + std::to_string(e.index) + "]";
        if (std::find(kKnownTags.begin(), kKnownTags.end(), e.tag) == kKnownTags.end())
            fail(e.label + " is not a section of a texture map");
        if (offset > bytes.size() || stored > bytes.size() - offset)
            fail(e.label + " lies outside the file");
        if (e.raw_len > kMaxRawSection) fail(e.label + " is too large");
        if (e.flags & ~(kFlagZlib | kFlagSourceCoded))
            fail(e.label + " has unknown flags " + std::to_string(e.flags));
        if (e.flags & kFlagSourceCoded) {
            if (e.tag != "CELL")
                fail(e.label + " is marked coded against the source: only cell images are");
            if (version < kSourceCodedVersion)
                fail(e.label + " is coded against the source in a map of format version " +
                     std::to_string(version) + " (it came with version " +
                     std::to_string(kSourceCodedVersion) + ")");
        }
        count_raw(e.raw_len);
        if (!where_is.emplace(std::pair{e.tag, e.index}, entries.size()).second)
            fail(e.label + " appears twice");
        e.payload = bytes.subspan(size_t(offset), stored);
        entries.push_back(std::move(e));
    }
    const auto inflate = [&](const Entry& e) {
        if (crc_of(e.payload) != e.crc && kVerifyChecksums)
            fail(e.label + " is corrupted (checksum mismatch)");
        std::vector<uint8_t> data;
        if (e.flags & kFlagZlib) {
            data.resize(e.raw_len);
            uLongf out_len = e.raw_len;
            if (uncompress(data.data(), &out_len, e.payload.data(), uLong(e.payload.size())) !=
                    Z_OK ||
                out_len != e.raw_len)
                fail(e.label + " does not decompress to its recorded length");
        } else {
            if (e.payload.size() != e.raw_len) fail(e.label + " has inconsistent lengths");
            data.assign(e.payload.begin(), e.payload.end());
        }
        return data;
    };
    // Then, from the small META section alone, how many cell images the map holds: a section
    // no map of that many could use is refused before anything large is inflated (three of
    // them, each under the size cap, once cost a load 768 MB before the refusal).
    {
        const auto meta = where_is.find({"META", 0});
        if (meta == where_is.end()) fail("section META[0] is missing");
        if (entries[meta->second].raw_len > kMaxMetaBytes) fail("section META[0] is too large");
        const std::vector<uint8_t> data = inflate(entries[meta->second]);
        Reader r(data, where + " section META[0]");
        const auto cw = r.le<uint32_t>("cell width"), ch = r.le<uint32_t>("cell height");
        const auto images = r.le<uint32_t>("cell image count");
        // Coded cell images decode to their pixels: those count against the limit too.
        if (cw <= uint32_t(kMaxCellSide) && ch <= uint32_t(kMaxCellSide))
            for (const Entry& e : entries)
                if (e.flags & kFlagSourceCoded) count_raw(8 + uint64_t(cw) * ch * 3);
        for (const Entry& e : entries) {
            const bool per_image = e.tag == "CELL" || e.tag == "PATA" || e.tag == "PATB" ||
                                   e.tag == "OVLA" || e.tag == "OVLB";
            if (per_image ? e.index >= images : e.index != 0)
                fail(e.label + " is not part of this map");
        }
    }
    // Then each section, inflated once and kept once.
    std::vector<Section> ordered;  // file order, for the content hash
    std::vector<uint8_t> ident;
    std::vector<bool> used(entries.size(), false);
    std::vector<size_t> slot(entries.size(), SIZE_MAX);
    for (size_t i = 0; i < entries.size(); ++i) {
        const Entry& e = entries[i];
        std::vector<uint8_t> data = inflate(e);
        if (e.tag == "IDNT") {
            ident = std::move(data);
        } else {
            slot[i] = ordered.size();
            ordered.push_back({e.tag, e.index, std::move(data)});
        }
    }
    auto section = [&](const char* tag, uint32_t index) -> Reader {
        auto it = where_is.find({tag, index});
        const std::string label = std::string("section ") + tag + "[" + std::to_string(index) + "]";
        if (it == where_is.end()) whole.fail(label + " is missing");
        used[it->second] = true;
        const std::vector<uint8_t>& data =
            slot[it->second] == SIZE_MAX ? ident : ordered[slot[it->second]].raw;
        return Reader(data, where + " " + label);
    };

    TextureMap map;
    uint32_t images = 0;
    {
        Reader r = section("META", 0);
        const auto cw = r.le<uint32_t>("cell width"), ch = r.le<uint32_t>("cell height");
        images = r.le<uint32_t>("cell image count");
        if (cw < 8 || ch < 8 || cw > uint32_t(kMaxCellSide) || ch > uint32_t(kMaxCellSide))
            r.fail("cell size " + std::to_string(cw) + "x" + std::to_string(ch) +
                   " is out of range");
        if (images == 0 || images > kMaxCellImages)
            r.fail("cell image count " + std::to_string(images) + " is out of range (1 to " +
                   std::to_string(kMaxCellImages) + ")");
        map.cell_width = int(cw), map.cell_height = int(ch);
        map.build.seed = r.le<uint64_t>("build seed");
        map.build.exemplar_width = int(r.le<uint32_t>("exemplar width"));
        map.build.exemplar_height = int(r.le<uint32_t>("exemplar height"));
        map.build.patches_requested = int(r.le<uint32_t>("patches requested"));
        map.build.candidates = int(r.le<uint32_t>("candidates"));
        map.build.active_per_cell = r.f64("active patches per cell");
        r.done();
    }
    if (where_is.count({"PHYS", 0})) {
        Reader r = section("PHYS", 0);
        const double dpi = r.f64("dpi"), exemplar_dpi = r.f64("exemplar dpi");
        const double grain = r.f64("grain");
        r.done();
        if (!(grain >= 0 && grain <= kMaxSourceSide))
            r.fail("grain " + std::to_string(grain) + " px is out of range");
        if (!(dpi >= kMinDpi && dpi <= kMaxDpi))
            r.fail("dpi " + std::to_string(dpi) + " is out of range");
        if (!(exemplar_dpi == 0 || (exemplar_dpi >= kMinDpi && exemplar_dpi <= kMaxDpi)))
            r.fail("exemplar dpi " + std::to_string(exemplar_dpi) + " is out of range");
        map.build.dpi = dpi, map.build.exemplar_dpi = exemplar_dpi, map.build.grain = grain;
    }
    if (where_is.count({"CSET", 0}) || images != 1) {
        Reader r = section("CSET", 0);
        const auto k = r.le<uint32_t>("corner colours");
        const auto v = r.remaining() > 0 ? r.le<uint32_t>("variants") : 1u;
        const auto rule = r.remaining() > 0 ? r.le<uint32_t>("variant rule") : 0u;
        r.done();
        if (k < 2 || k > uint32_t(kMaxCornerColours))
            r.fail("corner colours " + std::to_string(k) + " is out of range (2 to " +
                   std::to_string(kMaxCornerColours) + ")");
        if (v < 1 || v > uint32_t(kMaxVariants))
            r.fail("variants " + std::to_string(v) + " is out of range (1 to " +
                   std::to_string(kMaxVariants) + ")");
        if (rule > uint32_t(TextureMap::VariantRule::plain_in_four))
            r.fail("variant rule " + std::to_string(rule) +
                   " is unknown (0 parity, 1 break twins, 2 hashed, 3 plain cells in four)");
        if (rule != 0 && version < 3)
            r.fail("variant rule " + std::to_string(rule) + " in a map of format version " +
                   std::to_string(version) + " (it came with version 3)");
        if (rule != 0 && v < 2)
            r.fail("variant rule " + std::to_string(rule) + " needs 2 variants, the map has " +
                   std::to_string(v));
        const auto variant_rule = TextureMap::VariantRule(rule);
        if (const size_t needed = detail::cell_image_count(k, v, variant_rule); needed != images)
            r.fail(std::to_string(k) + " corner colours" + (v > 1 ? " in 2 variants" : "") +
                   (variant_rule == TextureMap::VariantRule::plain_in_four ? ", plain ones in 4,"
                                                                           : "") +
                   " need " + std::to_string(needed) + " cell images, the map holds " +
                   std::to_string(images));
        map.corner_colours = int(k), map.variants = int(v);
        map.variant_rule = variant_rule;
    }
    {
        Reader r = section("SRCE", 0);
        map.source = read_image(r, kMaxSourceSide);
        r.done();
    }
    for (uint32_t t = 0; t < images; ++t) {
        CellImage c;
        Reader img = section("CELL", t);
        if (const size_t i = where_is.at({"CELL", t}); entries[i].flags & kFlagSourceCoded) {
            // Decoded, and its pixels kept in place of the code for the content hash.
            std::vector<uint8_t>& raw = ordered[slot[i]].raw;
            c.pixels = detail::decode_cell_image(raw, map.source, {map.cell_width, map.cell_height},
                                                 where + " " + entries[i].label);
            Writer plain;
            write_image(plain, c.pixels);
            raw = std::move(plain.bytes);
            map.cell_storage = TextureMap::CellStorage::against_source;
        } else {
            c.pixels = read_image(img, kMaxCellSide);
            img.done();
        }
        if (c.pixels.cols != map.cell_width || c.pixels.rows != map.cell_height)
            img.fail("cell image size differs from the cell size");
        Reader pa = section("PATA", t), pb = section("PATB", t);
        c.a = read_patches(pa, map), c.b = read_patches(pb, map);
        pa.done(), pb.done();
        Reader oa = section("OVLA", t), ob = section("OVLB", t);
        read_overlaps(oa, c.a), read_overlaps(ob, c.b);
        oa.done(), ob.done();
        map.cell_images.push_back(std::move(c));
    }
    {
        Reader r = section("IDNT", 0);
        auto id = r.take(32, "map id");
        std::copy(id.begin(), id.end(), map.id.begin());
        r.done();
    }
    for (size_t i = 0; i < entries.size(); ++i)
        if (!used[i]) fail(entries[i].label + " is not part of this map");
    if (content_hash(ordered) != map.id && kVerifyChecksums)
        fail("content does not match its map id (file altered)");
    return map;
}

void save_texture_map(const TextureMap& map, const std::filesystem::path& path) {
    const std::vector<uint8_t> bytes = encode_texture_map(map);
    const std::filesystem::path tmp = path.string() + ".partial";
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out)
            throw MapFileError("cannot write texture map '" + path.string() +
                               "': " + std::strerror(errno));
        out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        out.flush();
        if (!out)
            throw MapFileError("cannot write texture map '" + path.string() +
                               "': " + std::strerror(errno));
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) throw MapFileError("cannot write texture map '" + path.string() + "': " + ec.message());
}

TextureMap load_texture_map(const std::filesystem::path& path) {
    const std::string name = "texture map '" + path.string() + "'";
    // Non-blocking, so that a FIFO does not hang the open; then regular files only, and no
    // larger than a map can be, before anything is read (/dev/zero reads for ever).
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) throw MapFileError("cannot read " + name + ": " + std::strerror(errno));
    struct Closer {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{fd};
    struct stat st {};
    if (::fstat(fd, &st) != 0)
        throw MapFileError("cannot read " + name + ": " + std::strerror(errno));
    if (!S_ISREG(st.st_mode)) throw MapFileError(name + " is not a regular file");
    if (st.st_size == 0) throw MapFileError(name + " is an empty file");
    if (uint64_t(st.st_size) > kMaxFileBytes)
        throw MapFileError(name + " is " + std::to_string(uint64_t(st.st_size) >> 20) +
                           " MiB, over the " + std::to_string(kMaxFileBytes >> 20) +
                           " MiB a texture map can be");
    std::vector<uint8_t> bytes(size_t(st.st_size));
    size_t got = 0;
    while (got < bytes.size()) {
        const ssize_t n = ::read(fd, bytes.data() + got, bytes.size() - got);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) throw MapFileError("cannot read " + name + ": " + std::strerror(errno));
        if (n == 0) throw MapFileError(name + " shrank while it was read");
        got += size_t(n);
    }
    return decode_texture_map(bytes, path.string());
}

}  // namespace tilejet::synth
