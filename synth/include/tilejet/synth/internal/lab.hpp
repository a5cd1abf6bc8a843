#pragma once

#include <opencv2/core/mat.hpp>

namespace tilejet::synth::detail {

// CIELab (D65) as CV_32FC3 from 8-bit R,G,B: L in [0, 100]. Costs of the build are distances
// in this space, where equal numbers mean roughly equally visible differences.
cv::Mat to_lab(const cv::Mat& rgb);

}  // namespace tilejet::synth::detail
