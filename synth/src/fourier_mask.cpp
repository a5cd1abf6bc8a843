#include "tilejet/synth/fourier_mask.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace tilejet::synth {

namespace {

// The Hann window's main lobe spans +-2 bins: anything that close to DC is the image's slow
// shading leaking, not structure.
constexpr int kMinBin = 2;

using Complex = std::complex<double>;

// Signed frequency (in bins) of DFT index k of an n-point transform.
int signed_bin(int k, int n) {
    return k <= n / 2 ? k : k - n;
}

// The windowed image's spectrum at a frequency between bins, by the DFT's defining sum (made
// separable: one pass along x per row, then one along y).
Complex spectrum_at(const cv::Mat& windowed, cv::Point2d f) {
    const double tau = 2 * std::numbers::pi;
    Complex total = 0;
    for (int y = 0; y < windowed.rows; ++y) {
        const double* row = windowed.ptr<double>(y);
        Complex sum = 0;
        for (int x = 0; x < windowed.cols; ++x)
            sum += row[x] * std::polar(1.0, -tau * f.x * x);
        total += sum * std::polar(1.0, -tau * f.y * y);
    }
    return total;
}

// Offset of a peak from its bin, in (-0.5, 0.5), by a parabola through the log magnitudes of
// the bin and its two neighbours: for a Hann-windowed sinusoid the main lobe is close to a
// Gaussian, whose logarithm the parabola fits exactly.
double parabolic_offset(double left, double centre, double right) {
    const double l = std::log(left + 1e-12), c = std::log(centre + 1e-12),
                 r = std::log(right + 1e-12);
    const double curvature = l - 2 * c + r;
    if (curvature >= 0) return 0;
    return std::clamp(0.5 * (l - r) / curvature, -0.5, 0.5);
}

}  // namespace

FourierMask find_fourier_mask(const cv::Mat& rgb, int count) {
    CV_Assert(rgb.type() == CV_8UC3 && count >= 0);
    cv::Mat grey, window;
    cv::cvtColor(rgb, grey, cv::COLOR_RGB2GRAY);
    grey.convertTo(grey, CV_64F);
    grey -= cv::mean(grey);
    cv::createHanningWindow(window, grey.size(), CV_64F);
    const cv::Mat windowed = grey.mul(window);
    const double window_sum = cv::sum(window)[0];

    cv::Mat spectrum, planes[2], magnitude;
    cv::dft(windowed, spectrum, cv::DFT_COMPLEX_OUTPUT);
    cv::split(spectrum, planes);
    cv::magnitude(planes[0], planes[1], magnitude);
    const int w = magnitude.cols, h = magnitude.rows;
    auto mag = [&](int kx, int ky) {
        return magnitude.at<double>((ky % h + h) % h, (kx % w + w) % w);
    };

    // Local maxima in one half-plane (a real image's spectrum is conjugate-symmetric).
    std::vector<std::pair<double, cv::Point>> peaks;
    for (int ky = 0; ky < h; ++ky)
        for (int kx = 0; kx < w; ++kx) {
            const int sx = signed_bin(kx, w), sy = signed_bin(ky, h);
            if (!(sy > 0 || (sy == 0 && sx > 0))) continue;
            if (std::abs(sx) <= kMinBin && std::abs(sy) <= kMinBin) continue;
            const double v = mag(kx, ky);
            bool is_max = v > 0;
            for (int dy = -1; dy <= 1 && is_max; ++dy)
                for (int dx = -1; dx <= 1 && is_max; ++dx)
                    if ((dx || dy) && mag(kx + dx, ky + dy) > v) is_max = false;
            if (is_max) peaks.emplace_back(v, cv::Point(sx, sy));
        }
    std::stable_sort(peaks.begin(), peaks.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
    if (peaks.size() > size_t(count)) peaks.resize(size_t(count));

    FourierMask mask;
    for (const auto& [v, bin] : peaks) {
        const double dx = parabolic_offset(mag(bin.x - 1, bin.y), v, mag(bin.x + 1, bin.y));
        const double dy = parabolic_offset(mag(bin.x, bin.y - 1), v, mag(bin.x, bin.y + 1));
        FourierComponent c;
        c.frequency = {(bin.x + dx) / w, (bin.y + dy) / h};
        // A cos(2 pi f.p + phi) sums to (A / 2) e^{i phi} times the window's sum at f.
        const Complex at = spectrum_at(windowed, c.frequency);
        c.amplitude = 2 * std::abs(at) / window_sum;
        c.phase = std::arg(at);
        mask.components.push_back(c);
    }
    return mask;
}

cv::Mat FourierMask::evaluate(cv::Size size) const {
    const double tau = 2 * std::numbers::pi;
    cv::Mat out(size, CV_32F, cv::Scalar(0));
    for (const FourierComponent& c : components)
        for (int y = 0; y < size.height; ++y) {
            float* row = out.ptr<float>(y);
            const double row_phase = tau * c.frequency.y * y + c.phase;
            for (int x = 0; x < size.width; ++x)
                row[x] += float(c.amplitude * std::cos(tau * c.frequency.x * x + row_phase));
        }
    return out;
}

cv::Mat FourierMask::evaluate_8bit(cv::Size size) const {
    cv::Mat out;
    const cv::Mat values = evaluate(size);
    double lo = 0, hi = 0;
    cv::minMaxLoc(values, &lo, &hi);
    if (hi - lo < 1e-9) return cv::Mat(size, CV_8U, cv::Scalar(128));
    values.convertTo(out, CV_8U, 255 / (hi - lo), -lo * 255 / (hi - lo));
    return out;
}

}  // namespace tilejet::synth
