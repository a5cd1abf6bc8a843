#pragma once

#include <filesystem>
#include <opencv2/core/mat.hpp>

namespace tilejet::cli {

// Writes an 8-bit R,G,B image as .png, or as .raw (interleaved R,G,B rows, no header).
// Throws std::runtime_error naming the file on any other extension or a failed write.
void write_rgb_image(const cv::Mat& rgb, const std::filesystem::path& path);

}  // namespace tilejet::cli
