#pragma once

// Plain image quilting (Efros and Freeman 2001) of an exemplar to any size: the offline
// reference the quality report compares tilejet with, and the way a factory's canvas is made.

#include <cstdint>
#include <opencv2/core/mat.hpp>

namespace tilejet::synth {

struct QuiltedImage {
    cv::Mat rgb;  // CV_8UC3, R,G,B
    // CV_32S: for each pixel, the exemplar pixel it was copied from, as y * exemplar.cols + x.
    // Two neighbours not copied from neighbouring exemplar pixels meet across a quilting seam.
    cv::Mat provenance;
};

// Quilts `exemplar` (CV_8UC3 R,G,B) to `size`. `block` 0 means the block a texture map with
// `cell`-px cells quilts its cell image with (cell / 4, at least 8); overlap is a sixth of it.
// The result wraps toroidally, like a cell image. Throws SynthError when the exemplar is too
// small for the blocks.
QuiltedImage quilt_texture(const cv::Mat& exemplar, cv::Size size, uint64_t seed, int block);

// Quilts `exemplar` (CV_8UC3 R,G,B) to an image of any `size` that does not wrap (tilejet synth
// --method quilt). `block` 0: a quarter of the exemplar's smaller side, at least 8 px.
cv::Mat quilt_image(const cv::Mat& exemplar, cv::Size size, uint64_t seed, int block = 0);

// The block size the map build quilts `cell`-px cell images with.
int quilt_block_for_cell(int cell);

}  // namespace tilejet::synth
