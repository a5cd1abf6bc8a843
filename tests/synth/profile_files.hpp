#pragma once

// Image files with an embedded ICC profile, written byte by byte as image editors write them,
// for the exemplar intake's tests (synth's plumbing, colour's conversion).

#include <opencv2/core/mat.hpp>
#include <string>

namespace tilejet::test {

inline constexpr const char* kAdobeRgbProfile =
    "/usr/share/color/icc/compatibleWithAdobeRGB1998.icc";

// The whole content of a file.
std::string file_text(const char* path);

// One PNG chunk: length, `type` (four letters), `data`, and the CRC of type and data.
std::string png_chunk(const std::string& type, const std::string& data);

// A PNG of `rgb` (R,G,B) with `icc` in an iCCP chunk right after IHDR; `break_zlib` damages the
// chunk's compressed profile (keeping the chunk's CRC right, so only the profile is broken).
std::string png_with_profile(const cv::Mat& rgb, const std::string& icc, bool break_zlib = false);

// A JPEG of `rgb` (R,G,B) with `icc` in one APP2 ICC_PROFILE segment.
std::string jpeg_with_profile(const cv::Mat& rgb, const std::string& icc);

// 32x32 saturated colours, where Adobe RGB and sRGB differ most.
cv::Mat saturated_swatches();

}  // namespace tilejet::test
