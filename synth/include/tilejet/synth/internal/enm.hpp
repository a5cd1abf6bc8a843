#pragma once

// Exact neighbourhood matching (docs/design.md section 7): per-pixel synthesis in scan order that
// searches only where the exemplar continues a neighbour exactly, instead of everywhere.

#include <cstdint>
#include <opencv2/core/mat.hpp>

namespace tilejet::synth {

struct EnmParams {
    // The causal neighbourhood compared: the `radius` rows above (2 radius + 1 wide) and the
    // `radius` pixels to the left. 2 gives 12 pixels.
    int radius = 2;
    // How far (R,G,B Euclidean, 8-bit units) a neighbour's colour may be from an exemplar
    // pixel's and still count as a match; 0: exactly equal.
    int tolerance = 0;
    // Brute force compares every exemplar position at every pixel: the baseline the benchmark
    // measures the exact matching against, with the same neighbourhood and choice rule.
    enum class Search { ExactMatch, BruteForce } search = Search::ExactMatch;
};

// Synthesizes `size` from `exemplar` (CV_8UC3 R,G,B), starting from a random exemplar block at
// the top left. Each next pixel in scan order takes the exemplar pixel whose causal
// neighbourhood is closest (L2) to the output's, among the candidates: for each synthesized
// direct neighbour (left, and the three above) at offset d with colour c, the positions p - d
// where the exemplar has colour c at p (found in a colour index). No candidate: a random one.
cv::Mat synthesize_enm(const cv::Mat& exemplar, cv::Size size, uint64_t seed,
                       const EnmParams& params = {});

}  // namespace tilejet::synth
