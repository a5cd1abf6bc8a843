#pragma once

#include <filesystem>
#include <opencv2/core/mat.hpp>

#include "tilejet/synth/error.hpp"

namespace tilejet::synth {

// Limits on exemplars: smaller cannot hold a texture, larger belongs to the canvas workflow
// tilejet replaces and would make maps far beyond the ~1 MB a line wants.
inline constexpr int kMinExemplarSide = 16;
inline constexpr int64_t kMaxExemplarPixels = int64_t(16) << 20;

// Reads a PNG, JPEG or TIFF exemplar (8 or 16 bit, grey, RGB or with alpha) as 8-bit RGB.
// Throws SynthError naming the file when it cannot be read, decoded, or is out of limits.
cv::Mat load_exemplar(const std::filesystem::path& path);

// Checks an in-memory exemplar (CV_8UC3 RGB) against the limits; `name` is used in messages.
void check_exemplar(const cv::Mat& rgb, const std::string& name);

}  // namespace tilejet::synth
