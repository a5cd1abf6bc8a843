#pragma once

#include <cstdint>
#include <filesystem>
#include <opencv2/core/mat.hpp>
#include <vector>

namespace tilejet::colour {

// Writes 8-bit-per-ink CMYK (CV_8UC4) as a TIFF with the output profile embedded, as prepress
// and RIP software expect. Throws ColourError naming the file.
void write_cmyk_tiff(const cv::Mat& cmyk, const std::vector<uint8_t>& icc_profile,
                     const std::filesystem::path& path);

struct CmykTiff {
    cv::Mat cmyk;                      // CV_8UC4
    std::vector<uint8_t> icc_profile;  // empty when none is embedded
};
CmykTiff read_cmyk_tiff(const std::filesystem::path& path);

}  // namespace tilejet::colour
