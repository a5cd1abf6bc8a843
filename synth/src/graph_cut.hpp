#pragma once

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

namespace tilejet::synth::detail {

// The terminal weight that pins a pixel to one side of a cut.
inline constexpr float kForced = 1e9f;
// Added to every edge so that, where the two images agree exactly, the cut still prefers the
// shortest boundary instead of an arbitrary one.
inline constexpr float kEdgeFloor = 1e-3f;

// What a pixel of a graph-cut window must show, or whether the cut decides.
enum class Pin : uint8_t { Free, New, Old };

struct Cut {
    std::vector<uint8_t> take_new;  // per window pixel, row-major: 1 where the new image shows
    double total_cost = 0;          // the cut's cost: what max-flow minimises
    double mean_cost = 0;           // mean edge cost along the cut
    // Mean squared edge cost: a short stretch of great cost (a vein cut off square) weighs
    // more than in mean_cost, where a long calm rest of the cut dilutes it.
    double mean_square_cost = 0;
    float max_cost = 0;  // largest single edge cost along the cut
    size_t taken = 0;    // pixels that show the new image
};

// Windows at least this many pixels on their shorter side are cut coarse to fine (graph_cut.cpp).
inline constexpr int kBandedCutSide = 192;

enum class CutLevels : uint8_t {
    Auto,   // coarse to fine from kBandedCutSide px
    Whole,  // every pixel a node of one max-flow: the exact minimum, slow on large windows
};

// The min-cut (Boykov-Kolmogorov max-flow, OpenCV's GCGraph) between an old and a new image of
// the same window, CIELab CV_32FC3 both (Kwatra et al. 2003): the edge between neighbours s, t
// costs |old(s) - new(s)| + |old(t) - new(t)|, so the seam runs where the two agree.
// `pins` (one per pixel, row-major) force pixels to either side. Windows of kBandedCutSide px
// and more are cut at half resolution first and refined in a band around that cut: close to
// the exact cut, not always equal to it.
Cut min_cut(const cv::Mat& old_lab, const cv::Mat& new_lab, const std::vector<Pin>& pins,
            CutLevels levels);

}  // namespace tilejet::synth::detail
