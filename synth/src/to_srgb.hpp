#pragma once

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

namespace tilejet::synth::detail {

// Converts 8-bit R,G,B pixels described by ICC profile `icc` to sRGB in place (LittleCMS,
// relative colorimetric with black point compensation: the exemplar's look, on sRGB's white).
// A grey profile applies to the (equal) channels. `name` names the exemplar in errors.
void convert_to_srgb(cv::Mat& rgb, const std::vector<uint8_t>& icc, const std::string& name);

}  // namespace tilejet::synth::detail
