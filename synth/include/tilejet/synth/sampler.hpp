#pragma once

// Online: the infinite texture plane of (map, seed), pixel by pixel or region by region
// (docs/design.md section 3). Both give exactly the same bytes, on any number of threads.

#include <cstddef>
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "tilejet/synth/error.hpp"
#include "tilejet/synth/texture_map.hpp"

namespace tilejet::synth {

struct Rgb {
    uint8_t r, g, b;
    bool operator==(const Rgb&) const = default;
};

// A rectangle of the texture plane. Coordinates may be anywhere in [-2^31, 2^31].
struct Region {
    int64_t x = 0, y = 0;
    int width = 0, height = 0;
};

struct CellIndex {
    int64_t i = 0, j = 0;
    bool operator==(const CellIndex&) const = default;
};

// Samples single pixels. Keeps the active patch sets of the cells it visited last, so scanning
// neighbouring pixels is cheap; the memo never changes a result. One Sampler per thread.
class Sampler {
  public:
    Sampler(const TextureMap& map, uint64_t seed);
    Sampler(const Sampler&) = delete;  // it points into its own memo
    Sampler& operator=(const Sampler&) = delete;
    Rgb sample(int64_t x, int64_t y);  // for maps in RGB
    // The pixel's bytes in the map's own pixel format (R,G,B, or C,M,Y,K for a map converted
    // by the colour module). Valid while the map lives.
    const uint8_t* pixel(int64_t x, int64_t y);

  private:
    // What the per-pixel loop reads of one active patch, in one small contiguous array per cell:
    // a Patch spans two cache lines and sits behind three pointers.
    struct ShownPatch {
        int x, y, width, height;  // bounding box in cell coordinates
        int row_bytes;
        const uint8_t* bits;  // the patch's mask
        const uint8_t* src;   // source pixel shown at the bounding box's top-left
    };
    struct Memo {
        CellIndex cell = kNoCell;
        std::vector<ShownPatch> shown;  // the cell's active patches, in ascending index order
    };
    const Memo& memo(CellType type, CellIndex cell);
    const CellImage& image_of(CellIndex cell) const;
    const uint8_t* background(int64_t x, int64_t y);  // the cell image's pixel

    // No cell of the plane (plane_limits.hpp) has this index: marks a state not yet filled.
    static constexpr CellIndex kNoCell{INT64_MIN, INT64_MIN};
    // The state every pixel reads comes first, in one cache line, and leads straight to the
    // cell's ShownPatch array: three dependent loads fewer per pixel than through the memo and
    // the PatchSet (demo map, scan order: median 57 -> 37 ns/px, alternated runs).
    struct Current {  // the cell of each type the last pixel fell in, and its shown patches
        CellIndex cell = kNoCell;
        const ShownPatch* begin = nullptr;
        const ShownPatch* end = nullptr;
    };
    alignas(64) Current current_[2];
    struct Background {  // the cell whose image shows where no patch does
        CellIndex cell = kNoCell;
        const CellImage* image = nullptr;
    };
    Background background_;
    const TextureMap& map_;
    uint64_t seed_;
    size_t source_step_, source_elem_;
    static constexpr size_t kMemoSlots = 64;  // a 1024 px scan row meets ~20 cells of each type
    Memo memo_[2][kMemoSlots];
    std::vector<uint16_t> active_;  // scratch of memo(): the active set's indices
};

// The cell image cell (i, j) shows for this seed: by its corners' colours (corner_colours.hpp).
uint32_t cell_image_index(const TextureMap& map, uint64_t seed, CellIndex cell);

// The patches of `type` shown in cell `cell` for this seed: activated by hash, then overlaps
// removed. Indices into the PatchSet of the cell's image, ascending.
std::vector<uint16_t> active_patches(const TextureMap& map, uint64_t seed, CellType type,
                                     CellIndex cell);

// Which cell's diamond holds pixel (x, y), for each cell type.
CellIndex diamond_cell(const TextureMap& map, CellType type, int64_t x, int64_t y);

// Renders `region` as rows `stride` bytes apart, in the map's pixel format: interleaved 8-bit
// R,G,B, or C,M,Y,K for a map whose images the colour module converted.
// `threads` 0 means all cores.
void render_region(const TextureMap& map, uint64_t seed, const Region& region, uint8_t* out,
                   size_t stride, int threads = 0);
cv::Mat render_region(const TextureMap& map, uint64_t seed, const Region& region, int threads = 0);

}  // namespace tilejet::synth
