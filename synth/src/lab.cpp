#include "tilejet/synth/internal/lab.hpp"

#include <opencv2/imgproc.hpp>

namespace tilejet::synth::detail {

cv::Mat to_lab(const cv::Mat& rgb) {
    cv::Mat unit, lab;
    rgb.convertTo(unit, CV_32FC3, 1.0 / 255.0);
    cv::cvtColor(unit, lab, cv::COLOR_RGB2Lab);
    return lab;
}

}  // namespace tilejet::synth::detail
