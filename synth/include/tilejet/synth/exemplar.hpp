#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <vector>

#include "tilejet/synth/error.hpp"

namespace tilejet::synth {

// Limits on exemplars: smaller cannot hold a texture; larger than a 580 mm slab scanned at
// 360 dpi (8192 x 8192 px) would take the build past 8 GB.
inline constexpr int kMinExemplarSide = 16;
inline constexpr int64_t kMaxExemplarPixels = int64_t(64) << 20;

// Converts an exemplar's 8-bit R,G,B pixels, described by the ICC profile `icc` its file embeds,
// to sRGB in place; throws SynthError naming exemplar `name`. The colour module, which wraps
// LittleCMS, provides it: colour::exemplar_to_srgb.
using EmbeddedProfileConversion =
    std::function<void(cv::Mat& rgb, const std::vector<uint8_t>& icc, const std::string& name)>;

// Reads a PNG, JPEG or TIFF exemplar (8 or 16 bit, grey, RGB or with alpha) as 8-bit sRGB:
// pixels of a file that embeds an ICC profile go through `to_srgb` (a file with a profile and no
// conversion given is refused). Throws SynthError naming the file when it cannot be read,
// decoded, or is out of limits; an image larger than the limits is refused from its header,
// before its pixels are allocated.
cv::Mat load_exemplar(const std::filesystem::path& path, const EmbeddedProfileConversion& to_srgb);

// The exemplar's resolution in pixels per inch as its file records it: PNG pHYs, JPEG JFIF
// (APP0) or Exif (APP1), TIFF XResolution and ResolutionUnit. Nothing when the file records
// none (or only an aspect ratio). Throws SynthError naming the file when the record is damaged
// or the pixels are not square.
std::optional<double> read_exemplar_dpi(const std::filesystem::path& path);

// Resolutions a file or a map may claim, pixels per inch: real scans and photos lie between
// 10 and 10 000; beyond this wider range a figure is damage, not a resolution.
inline constexpr double kMinDpi = 1, kMaxDpi = 100000;

// The image's width and height as its header gives them (PNG IHDR, JPEG start of frame, TIFF
// tags), read before anything is decoded; nothing for other files.
std::optional<cv::Size> read_image_size(const std::filesystem::path& path);

// `rgb` (CV_8UC3) scanned at `from_dpi`, resampled for printing at `to_dpi`: area averaging
// when it shrinks, Lanczos when it grows. Throws SynthError naming `name`, before allocating,
// when the result would be out of the exemplar limits.
cv::Mat resample_exemplar(const cv::Mat& rgb, double from_dpi, double to_dpi,
                          const std::string& name);

// Checks an in-memory exemplar (CV_8UC3 RGB) against the limits; `name` is used in messages.
void check_exemplar(const cv::Mat& rgb, const std::string& name);

}  // namespace tilejet::synth
