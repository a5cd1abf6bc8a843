#pragma once

// The size an exemplar is analysed at (its grain, its lattice): at most kAnalysisSide px on its
// longer side. The analyses correlate the image with itself over every displacement by FFT, in
// doubles, zero-padded to twice its size: 2 GB for a 4096 px slab scan, 8 GB for an 8192 px
// one, while what they look for (structures a few to a few hundred px across at the print
// resolution) shows as well in an image a few thousand px across.
#include <algorithm>
#include <cmath>
#include <opencv2/core/mat.hpp>
#include <opencv2/imgproc.hpp>

namespace tilejet::synth::detail {

inline constexpr int kAnalysisSide = 2048;

// How many times larger `size` is than the size it is analysed at (1: analysed as it is).
inline double analysis_scale(cv::Size size) {
    return std::max(1.0, double(std::max(size.width, size.height)) / kAnalysisSide);
}

inline cv::Size analysis_size(cv::Size size) {
    const double scale = analysis_scale(size);
    return {std::max(1, int(std::lround(size.width / scale))),
            std::max(1, int(std::lround(size.height / scale)))};
}

// The image analysed in place of `rgb`: an area-averaged copy of analysis_size(), or `rgb`
// itself when it is small enough.
inline cv::Mat analysis_copy(const cv::Mat& rgb) {
    if (analysis_scale(rgb.size()) == 1) return rgb;
    cv::Mat smaller;
    cv::resize(rgb, smaller, analysis_size(rgb.size()), 0, 0, cv::INTER_AREA);
    return smaller;
}

}  // namespace tilejet::synth::detail
