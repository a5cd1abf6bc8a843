#include "tilejet/quality/periodicity.hpp"

#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "tilejet/synth/error.hpp"
#include "tilejet/synth/internal/lab.hpp"

namespace tilejet::quality {

namespace {

// Sum of `sat` (an integral image, one row and column larger than the image) over rect r.
double rect_sum(const cv::Mat& sat, cv::Rect r) {
    return sat.at<double>(r.y + r.height, r.x + r.width) - sat.at<double>(r.y, r.x + r.width) -
           sat.at<double>(r.y + r.height, r.x) + sat.at<double>(r.y, r.x);
}

}  // namespace

AutocorrelationPeak autocorrelation_peak(const cv::Mat& rgb, int min_lag) {
    if (rgb.type() != CV_8UC3 || rgb.empty())
        throw synth::SynthError("autocorrelation needs a non-empty 8-bit RGB image");
    const int w = rgb.cols, h = rgb.rows, mx = w / 2, my = h / 2;
    std::vector<cv::Mat> lab;
    cv::split(synth::detail::to_lab(rgb), lab);

    // Cross term for every lag: circular correlation of zero-padded images equals the linear
    // one. Channels are pooled by summing their products.
    const cv::Size dft(cv::getOptimalDFTSize(w + mx), cv::getOptimalDFTSize(h + my));
    cv::Mat cross;
    cv::Mat sat[3], sat_sq[3];
    for (int c = 0; c < 3; ++c) {
        cv::Mat ch;
        lab[size_t(c)].convertTo(ch, CV_64F);
        cv::integral(ch, sat[c], sat_sq[c], CV_64F, CV_64F);
        cv::Mat padded(dft, CV_64F, cv::Scalar(0)), spectrum, product;
        ch.copyTo(padded(cv::Rect(0, 0, w, h)));
        cv::dft(padded, spectrum);
        cv::mulSpectrums(spectrum, spectrum, product, 0, true);
        if (cross.empty())
            cross = product;
        else
            cross += product;
    }
    cv::Mat corr;  // corr(dy, dx) = sum_x I(x) I(x + d), lags taken modulo the DFT size
    cv::dft(cross, corr, cv::DFT_INVERSE | cv::DFT_SCALE | cv::DFT_REAL_OUTPUT);

    // rho over lags dx in [-mx, mx], dy in [0, my] (the other half-plane mirrors it).
    cv::Mat rho(my + 1, 2 * mx + 1, CV_64F, cv::Scalar(-2));
    for (int dy = 0; dy <= my; ++dy)
        for (int dx = -mx; dx <= mx; ++dx) {
            // Part A starts at (max(0,-dx), 0), part B = A shifted by (dx, dy).
            const cv::Rect a(std::max(0, -dx), 0, w - std::abs(dx), h - dy);
            const cv::Rect b = a + cv::Point(dx, dy);
            const double n = double(a.area());
            double cov = 0, var_a = 0, var_b = 0;
            for (int c = 0; c < 3; ++c) {
                const double sa = rect_sum(sat[c], a), sb = rect_sum(sat[c], b);
                var_a += rect_sum(sat_sq[c], a) - sa * sa / n;
                var_b += rect_sum(sat_sq[c], b) - sb * sb / n;
                cov -= sa * sb / n;
            }
            // The correlation at lag d sums I(p) I(p + d) over p in A.
            cov += corr.at<double>((dy + dft.height) % dft.height, (dx + dft.width) % dft.width);
            const double denominator = std::sqrt(std::max(var_a, 0.0) * std::max(var_b, 0.0));
            rho.at<double>(dy, dx + mx) = denominator > 0 ? cov / denominator : 0;
        }

    AutocorrelationPeak best{-1, {0, 0}};
    auto at = [&](int dy, int dx) {
        // Mirror into the stored half-plane: rho(-d) = rho(d).
        if (dy < 0) dy = -dy, dx = -dx;
        if (dy > my || dx < -mx || dx > mx) return -2.0;
        return rho.at<double>(dy, dx + mx);
    };
    for (int dy = 0; dy <= my; ++dy)
        for (int dx = -mx; dx <= mx; ++dx) {
            if (std::max(std::abs(dx), dy) < min_lag) continue;
            if (std::abs(dx) == mx || dy == my) continue;  // a peak needs all 8 neighbours
            if (dy == 0 && dx < 0) continue;
            const double v = at(dy, dx);
            if (v <= best.value) continue;
            bool peak = true;
            for (int ey = -1; ey <= 1 && peak; ++ey)
                for (int ex = -1; ex <= 1 && peak; ++ex)
                    if ((ey || ex) && at(dy + ey, dx + ex) >= v) peak = false;
            if (peak) best = {v, {dx, dy}};
        }
    if (best.value < -1) best = {0, {0, 0}};
    return best;
}

}  // namespace tilejet::quality
