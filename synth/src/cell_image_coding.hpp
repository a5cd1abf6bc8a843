#pragma once

// Cell images stored as what they copy from the map's source (docs/design.md section 2.7).
//
// A set's cell images are mosaics of source windows: of the 256 px demo design's 36 images, three
// 8 px squares in four are a window of the source pixel for pixel, and zlib, which finds no
// repeats in a photograph, stored them at 5.1 MB beside a 0.2 MB source. Coded here, each block
// of kCodingBlock px names a displacement into the source and keeps only its difference from
// that window, zero where it copied: zlib stores the zeros for almost nothing (1.5 MB). The
// pixels decoded are the very pixels coded, so renders, map ids and the sampler stay as they
// were; only the file is smaller.
//
// Coded form (little-endian): u32 width, u32 height, then per block in row-major order i16 dx,
// i16 dy (kNoPrediction: the block is its own residual), then width x height x 3 residual bytes,
// pixel minus prediction modulo 256, in R,G,B row-major order.

#include <cstdint>
#include <opencv2/core.hpp>
#include <span>
#include <string>
#include <vector>

namespace tilejet::synth::detail {

inline constexpr int kCodingBlock = 8;
inline constexpr int16_t kNoPrediction = INT16_MIN;

// Codes `cells` (CV_8UC3, all one size) against `source` (CV_8UC3): displacements found by
// looking the blocks' pixels up in the source, and by trying their neighbours'. Deterministic:
// the same bytes on every machine and thread count.
std::vector<std::vector<uint8_t>> code_cell_images(std::span<const cv::Mat> cells,
                                                   const cv::Mat& source);

// The cell image `coded` holds (CV_8UC3, `cell` px), or a MapFileError naming `where` and what is
// wrong: a size other than the cell's, a block copying from outside the source, missing or
// extra bytes.
cv::Mat decode_cell_image(std::span<const uint8_t> coded, const cv::Mat& source, cv::Size cell,
                          const std::string& where);

}  // namespace tilejet::synth::detail
