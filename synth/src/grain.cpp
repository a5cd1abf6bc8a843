#include "grain.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "analysis_size.hpp"

namespace tilejet::synth::detail {

namespace {
constexpr int kDirections = 64;
constexpr double kGone = 0.1;  // correlation below this: no longer the same structure
constexpr int kCellStep = 32;
constexpr int kSlabSide = 1024;  // exemplars this large may have cells of up to 640 px
}  // namespace

int cell_side_for_grain(double grain, bool lattice, int exemplar_side) {
    const double grains = lattice ? 3 : 4;
    const int side = int(std::lround(grains * grain / kCellStep)) * kCellStep;
    if (lattice) return std::clamp(side, 128, 192);
    return std::clamp(side, 256, exemplar_side >= kSlabSide ? 640 : 320);
}

double grain_size(const cv::Mat& rgb) {
    CV_Assert(rgb.type() == CV_8UC3);
    // The autocorrelation of a slab scan in full would take 2 GB (8192 px: 16 times that); its
    // largest structures show as well at a few thousand px across, in px `scale` times larger.
    const double scale = analysis_scale(rgb.size());
    if (scale > 1) return scale * grain_size(analysis_copy(rgb));
    cv::Mat grey;
    cv::cvtColor(rgb, grey, cv::COLOR_RGB2GRAY);
    grey.convertTo(grey, CV_64F);
    const int w = grey.cols, h = grey.rows;
    const double reach = std::min(w, h) / 3.0;
    cv::Scalar mean, sd;
    cv::meanStdDev(grey, mean, sd);
    if (sd[0] < 1e-6) return reach;  // flat: nothing to size
    grey -= mean[0];
    // Autocorrelation of all displacements by FFT, zero-padded so it does not wrap, each
    // divided by its overlap and the variance.
    const cv::Size size(cv::getOptimalDFTSize(2 * w), cv::getOptimalDFTSize(2 * h));
    cv::Mat padded(size, CV_64F, cv::Scalar(0)), spectrum, correlation;
    grey.copyTo(padded(cv::Rect(0, 0, w, h)));
    cv::dft(padded, spectrum);
    cv::mulSpectrums(spectrum, spectrum, spectrum, 0, true);
    cv::dft(spectrum, correlation, cv::DFT_INVERSE | cv::DFT_SCALE | cv::DFT_REAL_OUTPUT);
    const double variance = sd[0] * sd[0];
    auto at = [&](int dx, int dy) {
        const double overlap = double(w - std::abs(dx)) * (h - std::abs(dy));
        return correlation.at<double>((dy + size.height) % size.height,
                                      (dx + size.width) % size.width) /
               (overlap * variance);
    };
    double previous = 1;
    for (int r = 1; r <= int(reach); ++r) {
        double sum = 0;
        for (int k = 0; k < kDirections; ++k) {
            const double a = std::numbers::pi * k / kDirections;  // half the circle: symmetric
            sum += at(int(std::lround(r * std::cos(a))), int(std::lround(r * std::sin(a))));
        }
        const double value = sum / kDirections;
        if (value < kGone) return r - 1 + (previous - kGone) / std::max(1e-9, previous - value);
        previous = value;
    }
    return reach;
}

GrainDirection grain_direction(const cv::Mat& rgb) {
    CV_Assert(rgb.type() == CV_8UC3);
    if (analysis_scale(rgb.size()) > 1) return grain_direction(analysis_copy(rgb));
    cv::Mat grey, gx, gy;
    cv::cvtColor(rgb, grey, cv::COLOR_RGB2GRAY);
    grey.convertTo(grey, CV_32F);
    cv::Sobel(grey, gx, CV_32F, 1, 0);
    cv::Sobel(grey, gy, CV_32F, 0, 1);
    const double xx = cv::mean(gx.mul(gx))[0], yy = cv::mean(gy.mul(gy))[0],
                 xy = cv::mean(gx.mul(gy))[0];
    const double trace = xx + yy;
    if (trace < 1e-9) return {};  // flat: no direction
    // The tensor's main axis is the gradients' way; the grain's edges run square to it.
    const double gradient = 0.5 * std::atan2(2 * xy, xx - yy) * 180 / std::numbers::pi;
    return {std::sqrt((xx - yy) * (xx - yy) + 4 * xy * xy) / trace,
            std::fmod(gradient + 90 + 360, 180.0)};
}

double grain_alignment(const cv::Mat& rgb) {
    return grain_direction(rgb).alignment;
}

}  // namespace tilejet::synth::detail
