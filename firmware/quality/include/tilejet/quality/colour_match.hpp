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
    static constexpr int kPlotBins = 64;  // per channel, for the report's plots
    colour::LabColour mean;
    cv::Mat joint;                               // 3D, kBins^3, CV_32F, sums to 1
    std::array<std::vector<double>, 3> channel;  // L, a, b over the same ranges, each sums to 1
};
LabStatistics lab_statistics(const std::vector<cv::Mat>& images, int threads = 0);

struct ColourMatch {
    colour::LabColour exemplar_mean, wall_mean;
    double mean_delta_e2000 = 0;    // CIEDE2000 between the two mean colours
    double histogram_distance = 0;  // Bhattacharyya distance of the joint Lab histograms, 0..1
};
ColourMatch compare_colour(const LabStatistics& exemplar, const LabStatistics& wall);

}  // namespace tilejet::quality
