#pragma once

// Does the wall keep the exemplar's colour (docs/design.md section 8)? Quilting favours the calm,
// well-matching parts of an exemplar, so a synthesized wall can drift darker or greyer.

#include <array>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "tilejet/colour/ciede2000.hpp"

namespace tilejet::quality {

// Mean CIELab colour of images (CV_8UC3 R,G,B) and their joint CIELab histogram.
struct LabStatistics {
    static constexpr int kBins = 16;  // per axis of the joint histogram: L 0..100, a, b -128..128
    static constexpr int kPlotBins = 64;         // per channel, for the report's plots
    static constexpr int kLightnessBins = 1000;  // L* 0..100 in steps of 0.1, for its tails
    colour::LabColour mean;
    cv::Mat joint;                               // 3D, kBins^3, CV_32F, sums to 1
    std::array<std::vector<double>, 3> channel;  // L, a, b over the same ranges, each sums to 1
    std::vector<double> lightness;               // L* in kLightnessBins, sums to 1
};
LabStatistics lab_statistics(const std::vector<cv::Mat>& images, int threads = 0);

// The L* below which a share q of the pixels lie, interpolated within a bin.
double lightness_quantile(const LabStatistics& s, double q);
// Share of the pixels lighter than L* `l`, and darker than it.
double share_lighter(const LabStatistics& s, double l);
double share_darker(const LabStatistics& s, double l);

// The exemplar's lightest and darkest 5 % are its veins, flecks and pits: what makes the stone
// look like itself. A wall that holds much less of them is calmer than the stone even when its
// mean colour and its texture energy are close (a wall of the exemplar's calm background would
// pass both). On the exemplar both tails are 5 % by definition.
inline constexpr double kTailShare = 0.05;

struct ColourMatch {
    colour::LabColour exemplar_mean, wall_mean;
    double mean_delta_e2000 = 0;    // CIEDE2000 between the two mean colours
    double histogram_distance = 0;  // Bhattacharyya distance of the joint Lab histograms, 0..1
    // Share of the wall lighter than the exemplar's lightest kTailShare, and darker than its
    // darkest kTailShare: kTailShare each where the wall keeps the stone's extremes.
    double light_tail = 0, dark_tail = 0;
};
ColourMatch compare_colour(const LabStatistics& exemplar, const LabStatistics& wall);

}  // namespace tilejet::quality
