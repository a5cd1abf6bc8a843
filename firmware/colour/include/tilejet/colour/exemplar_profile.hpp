#pragma once

// Exemplars whose file embeds an ICC profile (a photo in Adobe RGB, a camera or scanner profile)
// are converted to sRGB on intake, so the colour module's default source profile is right for
// every map (docs/design.md section 4). The conversion lives here, where LittleCMS is wrapped;
// synth's exemplar intake takes it as a callback.

#include <cstdint>
#include <filesystem>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

namespace tilejet::colour {

// Converts 8-bit R,G,B pixels described by ICC profile `icc` to sRGB in place: relative
// colorimetric with black point compensation, the exemplar's look on sRGB's white. A grey
// profile applies to the (equal) channels. Throws synth::SynthError naming exemplar `name` when
// the profile is damaged, neither RGB nor grey, or cannot be converted.
void exemplar_to_srgb(cv::Mat& rgb, const std::vector<uint8_t>& icc, const std::string& name);

// synth::load_exemplar with embedded profiles converted by exemplar_to_srgb: what the CLI and
// the benchmarks read exemplars with.
cv::Mat load_exemplar(const std::filesystem::path& path);

}  // namespace tilejet::colour
