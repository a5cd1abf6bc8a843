#include "tilejet/quality/colour_match.hpp"

#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "tilejet/synth/internal/lab.hpp"
#include "tilejet/synth/internal/parallel_for.hpp"

namespace tilejet::quality {

namespace {

// Bin of a value in [lo, hi) split into n bins; values outside go to the end bins.
int bin(float v, float lo, float hi, int n) {
    return std::clamp(int((v - lo) / (hi - lo) * float(n)), 0, n - 1);
}

struct Partial {
    double sum[3] = {0, 0, 0};
    size_t pixels = 0;
    std::vector<double> joint, channel[3], lightness;
};

void accumulate(const cv::Mat& rgb, Partial& p) {
    constexpr int n = LabStatistics::kBins, m = LabStatistics::kPlotBins,
                  fine = LabStatistics::kLightnessBins;
    p.joint.assign(size_t(n * n * n), 0);
    for (auto& c : p.channel)
        c.assign(size_t(m), 0);
    p.lightness.assign(size_t(fine), 0);
    const cv::Mat lab = synth::detail::to_lab(rgb);
    for (int y = 0; y < lab.rows; ++y) {
        const cv::Vec3f* row = lab.ptr<cv::Vec3f>(y);
        for (int x = 0; x < lab.cols; ++x) {
            const cv::Vec3f v = row[x];
            for (int c = 0; c < 3; ++c)
                p.sum[c] += v[c];
            const int l = bin(v[0], 0, 100, n), a = bin(v[1], -128, 128, n),
                      b = bin(v[2], -128, 128, n);
            p.joint[size_t((l * n + a) * n + b)] += 1;
            p.channel[0][size_t(bin(v[0], 0, 100, m))] += 1;
            p.channel[1][size_t(bin(v[1], -128, 128, m))] += 1;
            p.channel[2][size_t(bin(v[2], -128, 128, m))] += 1;
            p.lightness[size_t(bin(v[0], 0, 100, fine))] += 1;
        }
    }
    p.pixels = lab.total();
}

}  // namespace

LabStatistics lab_statistics(const std::vector<cv::Mat>& images, int threads) {
    constexpr int n = LabStatistics::kBins, m = LabStatistics::kPlotBins,
                  fine = LabStatistics::kLightnessBins;
    std::vector<Partial> parts(images.size());
    synth::detail::parallel_for(images.size(), threads,
                                [&](size_t i) { accumulate(images[i], parts[i]); });
    Partial all;
    all.joint.assign(size_t(n * n * n), 0);
    for (auto& c : all.channel)
        c.assign(size_t(m), 0);
    all.lightness.assign(size_t(fine), 0);
    for (const Partial& p : parts) {
        for (int c = 0; c < 3; ++c) {
            all.sum[c] += p.sum[c];
            for (size_t k = 0; k < size_t(m); ++k)
                all.channel[c][k] += p.channel[c][k];
        }
        for (size_t k = 0; k < all.joint.size(); ++k)
            all.joint[k] += p.joint[k];
        for (size_t k = 0; k < size_t(fine); ++k)
            all.lightness[k] += p.lightness[k];
        all.pixels += p.pixels;
    }
    LabStatistics s;
    const double count = double(std::max<size_t>(1, all.pixels));
    s.mean = {all.sum[0] / count, all.sum[1] / count, all.sum[2] / count};
    const int dims[3] = {n, n, n};
    s.joint.create(3, dims, CV_32F);
    for (size_t k = 0; k < all.joint.size(); ++k)
        s.joint.ptr<float>()[k] = float(all.joint[k] / count);
    for (int c = 0; c < 3; ++c) {
        s.channel[size_t(c)] = all.channel[c];
        for (double& v : s.channel[size_t(c)])
            v /= count;
    }
    s.lightness = all.lightness;
    for (double& v : s.lightness)
        v /= count;
    return s;
}

namespace {
constexpr double kBinWidth = 100.0 / LabStatistics::kLightnessBins;
}

double lightness_quantile(const LabStatistics& s, double q) {
    double below = 0;  // share of the pixels in the bins before bin k
    for (size_t k = 0; k < s.lightness.size(); ++k) {
        const double in = s.lightness[k];
        if (in > 0 && below + in >= q)
            return (double(k) + std::clamp((q - below) / in, 0.0, 1.0)) * kBinWidth;
        below += in;
    }
    return 100;
}

double share_darker(const LabStatistics& s, double l) {
    // Pixels spread evenly within a bin: the bin l falls in counts in part.
    const double at = std::clamp(l / kBinWidth, 0.0, double(s.lightness.size()));
    const size_t whole = size_t(at);
    double share = 0;
    for (size_t k = 0; k < whole; ++k)
        share += s.lightness[k];
    if (whole < s.lightness.size()) share += s.lightness[whole] * (at - double(whole));
    return share;
}

double share_lighter(const LabStatistics& s, double l) {
    double total = 0;
    for (double v : s.lightness)
        total += v;
    return std::max(0.0, total - share_darker(s, l));
}

ColourMatch compare_colour(const LabStatistics& exemplar, const LabStatistics& wall) {
    ColourMatch m;
    m.exemplar_mean = exemplar.mean;
    m.wall_mean = wall.mean;
    m.mean_delta_e2000 = ciede2000(exemplar.mean, wall.mean);
    m.histogram_distance = cv::compareHist(exemplar.joint, wall.joint, cv::HISTCMP_BHATTACHARYYA);
    m.light_tail = share_lighter(wall, lightness_quantile(exemplar, 1 - kTailShare));
    m.dark_tail = share_darker(wall, lightness_quantile(exemplar, kTailShare));
    return m;
}

}  // namespace tilejet::quality
