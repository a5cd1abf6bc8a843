#pragma once

// A wall of equal tiles as the quality report sees it (docs/design.md section 8), made by tilejet
// or by one of the methods it is compared with: a factory canvas, the bare cell image, or
// quilting every tile on its own.

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "tilejet/synth/texture_map.hpp"

namespace tilejet::quality {

// Bits of a seam map: which neighbour pairs a seam (a cut between two copied pieces) runs
// between.
inline constexpr uint8_t kSeamRight = 1;  // between (x, y) and (x + 1, y)
inline constexpr uint8_t kSeamBelow = 2;  // between (x, y) and (x, y + 1)

struct Wall {
    cv::Size tile;
    int columns = 1;             // tiles per wall row; tile k lies at (k % columns, k / columns)
    std::vector<cv::Mat> tiles;  // CV_8UC3 R,G,B, each of size `tile`, in laying order
    // Per tile, CV_8U of kSeam* bits; empty when the method's seams are not known.
    std::vector<cv::Mat> seams;

    int rows() const { return int((tiles.size() + size_t(columns) - 1) / size_t(columns)); }
    cv::Size laid_size() const { return {columns * tile.width, rows() * tile.height}; }
    // The laid wall (or `area` of it) at full resolution; joints without a tile are grey.
    cv::Mat laid(cv::Rect area) const;
};

struct WallSpec {
    int tiles = 0;
    cv::Size tile;
    int columns = 0;  // 0: about square (ceil(sqrt(tiles)))
    uint64_t seed = 0;
    int threads = 0;  // 0: all cores; never changes a byte
};

// Tiles 0..n-1 of job `seed` in tilejet's wall layout: one contiguous region of the plane.
Wall tilejet_wall(const synth::TextureMap& map, const WallSpec& spec);
// The same tile regions showing only the cell image: what tilejet would be without patches.
Wall cell_wall(const synth::TextureMap& map, const WallSpec& spec);
// Today's factory practice: one canvas (`canvas` px, quilted once from the exemplar with
// `block`-px blocks) and every tile cropped from it at a random position.
Wall canvas_wall(const cv::Mat& exemplar, const WallSpec& spec, cv::Size canvas, int block);
// Every tile quilted on its own from the exemplar: the offline quality reference.
Wall quilt_wall(const cv::Mat& exemplar, const WallSpec& spec, int block);

// Seam bits of a quilted image from its provenance (see QuiltedImage); `exemplar_width` is the
// width of the exemplar the provenance indexes.
cv::Mat seams_from_provenance(const cv::Mat& provenance, int exemplar_width);
// Seam bits from patch labels (see render_patch_labels): wherever two neighbours' labels differ.
cv::Mat seams_from_labels(const cv::Mat& labels);

}  // namespace tilejet::quality
