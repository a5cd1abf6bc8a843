#pragma once

#include <cstdint>
#include <filesystem>
#include <opencv2/core/mat.hpp>
#include <vector>

namespace tilejet::cli {

// Writes an 8-bit R,G,B image as .png, or as .raw (interleaved R,G,B rows, no header).
// Throws std::runtime_error naming the file on any other extension or a failed write.
void write_rgb_image(const cv::Mat& rgb, const std::filesystem::path& path);

// Writes 8-bit C,M,Y,K as .tif (with `icc_profile` embedded) or .raw (interleaved C,M,Y,K rows).
void write_cmyk_image(const cv::Mat& cmyk, const std::vector<uint8_t>& icc_profile,
                      const std::filesystem::path& path);

}  // namespace tilejet::cli
