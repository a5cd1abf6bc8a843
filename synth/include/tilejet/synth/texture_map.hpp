#pragma once

// The texture map: everything the online sampler needs to compute any pixel of a design's
// infinite texture plane (docs/design.md section 1). Built once per design by build_texture_map(),
// stored as one file by save_texture_map(), read back by load_texture_map().

#include <array>
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

namespace tilejet::synth {

// A horizontal run of covered pixels in one row of a patch mask, relative to the mask's
// bounding box. Region rendering copies runs with memcpy instead of testing bits.
struct MaskRun {
    uint16_t row;
    uint16_t x;
    uint16_t length;
};

// Bit (px, py) of a row-major mask of one bit per pixel whose rows are `row_bytes` long.
inline bool mask_bit(const uint8_t* bits, int row_bytes, int64_t px, int64_t py) {
    return (bits[size_t(py) * size_t(row_bytes) + size_t(px >> 3)] >> (px & 7)) & 1;
}

// One graph-cut patch: a binary mask placed in cell coordinates (relative to the origin of the
// cell it is shown in; it may hang over the cell's edge but never leaves the cell's diamond)
// and the source pixel that the mask's top-left corner copies.
struct Patch {
    int x = 0, y = 0;           // bounding box top-left, cell coordinates
    int width = 0, height = 0;  // bounding box size
    int src_x = 0, src_y = 0;   // source pixel shown at the bounding box's top-left
    // Cost of the patch's cut, lower is better: its largest single edge cost, or in a cell set
    // the mean edge cost along it (candidate_patch.hpp, strip_continuation.hpp).
    float seam_cost = 0;
    std::vector<uint8_t> bits;       // row-major, one bit per pixel, each row padded to whole bytes
    std::vector<MaskRun> runs;       // derived from bits, sorted by row
    std::vector<uint32_t> row_runs;  // runs of row r are [row_runs[r], row_runs[r + 1])

    int row_bytes() const { return (width + 7) / 8; }
    bool covers(int px, int py) const {  // px, py relative to the bounding box
        return mask_bit(bits.data(), row_bytes(), px, py);
    }
    void derive_runs();
};

// Patches of one cell type (A or B) of one cell image, with the bit matrix of which of
// them overlap each other when placed in the same cell.
struct PatchSet {
    std::vector<Patch> patches;
    std::vector<uint64_t> overlap_bits;  // n x n, row-major, rows padded to 64-bit words
    uint64_t activation_threshold = 0;   // patch k of a cell is active when its hash is below this

    size_t size() const { return patches.size(); }
    size_t overlap_row_words() const { return (patches.size() + 63) / 64; }
    bool overlaps(size_t a, size_t b) const {
        return (overlap_bits[a * overlap_row_words() + b / 64] >> (b % 64)) & 1;
    }
};

enum class CellType : uint8_t { A = 0, B = 1 };

// An image of one cell's size with its own two patch sets. A map holds one, which wraps
// toroidally, or a corner-coloured set (docs/design.md section 9, cell_set.hpp): one image for each
// combination of its four corners' colours, any two of which meet seamlessly where their
// shared corners agree.
struct CellImage {
    cv::Mat pixels;  // CV_8UC3 R,G,B, or CV_8UC4 C,M,Y,K once converted for a line
    PatchSet a, b;
    const PatchSet& set(CellType t) const { return t == CellType::A ? a : b; }
};

// How the map was made; kept in the file so a map can be rebuilt and audited.
struct BuildRecord {
    uint64_t seed = 0;
    int exemplar_width = 0, exemplar_height = 0;
    int patches_requested = 0;
    int candidates = 0;
    double active_per_cell = 10;  // expected active patches per cell: eta = active_per_cell / |set|
    // The design's physical size: the print resolution the map is built for (its plane's pixels
    // per inch) and the exemplar's own, before it was resampled to that. 0: not recorded (maps
    // built before resolutions were, and library builds that give none).
    double dpi = 0, exemplar_dpi = 0;
    // The size of the exemplar's largest structures the default cell size came from, px; 0
    // when --cell gave it (or not recorded).
    double grain = 0;
};

struct TextureMap {
    int cell_width = 0, cell_height = 0;
    // K: every lattice vertex gets one of K colours by hash, and the cell image of a cell is
    // the one made for its corners' colours, cell_images[tl + K tr + K^2 bl + K^3 br]. K = 1:
    // one cell image everywhere (the maps of format version 1 and earlier).
    int corner_colours = 1;
    // V: cell images per combination of corner colours, cell_images[combination + K^4 v]. With
    // K = 2 and one image per combination, one edge in 16 and one vertex in 16 joined two
    // copies of one image: a motif doubled side by side. With V = 2 the variant rule below
    // keeps such neighbours apart (and with VariantRule::plain_in_four plain combinations have
    // four).
    int variants = 1;
    // Which variant a cell of a set of two shows (corner_colours.hpp).
    enum class VariantRule : uint32_t {
        // (i + j) mod 2: never one image across an edge, but across a vertex one in 16 (the
        // maps of 2026-11 and earlier).
        parity = 0,
        // The first unless a neighbour shows the same combination; then one of the parities
        // that parts the two (corner_colours.hpp). The second shows on about one cell in
        // five; no image twice across an edge, across a vertex a fifth as often as by parity.
        break_twins = 1,
        // As break_twins where a neighbour shows the same combination; elsewhere a variant by
        // integer hash of (map, seed, cell), so every image shows about equally often. With the
        // first variant wherever no twin stood, half the set showed on one cell in five and
        // a wall repeated its first 16 images: 5.9 % of a 36-tile wall's tile pairs shared a
        // quarter-tile window pixel for pixel, 4.3 % hashed (the corpus at map seeds 1 and 2,
        // session 30).
        hashed = 2,
        // As hashed, but a plain cell, whose four corners have one colour, shows one of four
        // variants. Plain cells are the only ones that can have twins across an edge and across
        // a vertex at once: four of one combination round a vertex (3 x 3 vertices of one
        // colour, one in 256) cannot all differ in two variants, and on the corpus such diagonal
        // twins, 1.3 % of diagonal pairs, were what was left of the cell grid (limestone's
        // periodicity 1.24 at map seed 2, session 31). With four, plain twins take the variant
        // (i mod 2) + 2 (j mod 2), and no two of the eight neighbours of any cell show one image.
        // The plain combinations' variants 2 and 3 follow the K^4 V others in cell_images
        // (corner_colours.hpp). Not built on a lattice (build.cpp).
        plain_in_four = 3,
    };
    VariantRule variant_rule = VariantRule::parity;
    // How the file stores the cell images: as pixels, or as what they copy from the source and
    // how they differ from it (cell_image_coding.hpp; format version 4), a third of the bytes
    // for a set. The pixels, and so renders and the map id, are the same either way.
    enum class CellStorage : uint32_t { pixels = 0, against_source = 1 };
    CellStorage cell_storage = CellStorage::pixels;
    cv::Mat source;  // CV_8UC3, R,G,B: what patches copy from (CV_8UC4 C,M,Y,K once converted)
    std::vector<CellImage> cell_images;
    BuildRecord build;
    std::array<uint8_t, 32> id{};  // SHA-256 of the content; seeds activation hashing

    uint64_t id64() const;       // first 8 bytes of the id, little-endian
    std::string id_hex() const;  // the full id in hex: the map's name in logs and job records
};

// Activation threshold for `active_per_cell` expected active patches among `set_size`:
// eta * 2^64 with eta = active_per_cell / set_size. Computed once at build time and stored in the
// map, so the sampler compares integers only and never depends on floating point.
uint64_t activation_threshold(double active_per_cell, size_t set_size);

}  // namespace tilejet::synth
