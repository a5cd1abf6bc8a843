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

namespace {

// Pearson correlation in CIELab, channels pooled, between an image and itself shifted by any lag
// (dx, dy) with |dx| < width, |dy| < height: the cross term of every lag by one FFT per channel
// (circular correlation of zero-padded images equals the linear one), the overlap's two parts'
// means and energies from summed-area tables.
class Autocorrelation {
  public:
    explicit Autocorrelation(const cv::Mat& rgb) : w_(rgb.cols), h_(rgb.rows) {
        if (rgb.type() != CV_8UC3 || rgb.empty())
            throw synth::SynthError("autocorrelation needs a non-empty 8-bit RGB image");
        std::vector<cv::Mat> lab;
        cv::split(synth::detail::to_lab(rgb), lab);
        dft_ = {cv::getOptimalDFTSize(w_ + w_ / 2), cv::getOptimalDFTSize(h_ + h_ / 2)};
        cv::Mat cross;
        for (int c = 0; c < 3; ++c) {
            cv::Mat ch;
            lab[size_t(c)].convertTo(ch, CV_64F);
            cv::integral(ch, sat_[c], sat_sq_[c], CV_64F, CV_64F);
            cv::Mat padded(dft_, CV_64F, cv::Scalar(0)), spectrum, product;
            ch.copyTo(padded(cv::Rect(0, 0, w_, h_)));
            cv::dft(padded, spectrum);
            cv::mulSpectrums(spectrum, spectrum, product, 0, true);
            if (cross.empty())
                cross = product;
            else
                cross += product;
        }
        // corr(dy, dx) = sum_x I(x) I(x + d), lags taken modulo the DFT size.
        cv::dft(cross, corr_, cv::DFT_INVERSE | cv::DFT_SCALE | cv::DFT_REAL_OUTPUT);
    }

    // The correlation at lag (dx, dy), |dx| <= width / 2 and |dy| <= height / 2 (the padding
    // holds those lags unwrapped).
    double at(int dx, int dy) const {
        if (dy < 0) dx = -dx, dy = -dy;  // rho(-d) = rho(d)
        // Part A starts at (max(0,-dx), 0), part B = A shifted by (dx, dy).
        const cv::Rect a(std::max(0, -dx), 0, w_ - std::abs(dx), h_ - dy);
        const cv::Rect b = a + cv::Point(dx, dy);
        const double n = double(a.area());
        double cov = 0, var_a = 0, var_b = 0;
        for (int c = 0; c < 3; ++c) {
            const double sa = rect_sum(sat_[c], a), sb = rect_sum(sat_[c], b);
            var_a += rect_sum(sat_sq_[c], a) - sa * sa / n;
            var_b += rect_sum(sat_sq_[c], b) - sb * sb / n;
            cov -= sa * sb / n;
        }
        // The correlation at lag d sums I(p) I(p + d) over p in A.
        cov += corr_.at<double>((dy + dft_.height) % dft_.height, (dx + dft_.width) % dft_.width);
        const double denominator = std::sqrt(std::max(var_a, 0.0) * std::max(var_b, 0.0));
        return denominator > 0 ? cov / denominator : 0;
    }

  private:
    int w_, h_;
    cv::Size dft_;
    cv::Mat corr_, sat_[3], sat_sq_[3];
};

}  // namespace

AutocorrelationPeak autocorrelation_peak(const cv::Mat& rgb, int min_lag) {
    const Autocorrelation auto_corr(rgb);
    const int mx = rgb.cols / 2, my = rgb.rows / 2;
    // rho over lags dx in [-mx, mx], dy in [0, my] (the other half-plane mirrors it).
    cv::Mat rho(my + 1, 2 * mx + 1, CV_64F, cv::Scalar(-2));
    for (int dy = 0; dy <= my; ++dy)
        for (int dx = -mx; dx <= mx; ++dx)
            rho.at<double>(dy, dx + mx) = auto_corr.at(dx, dy);

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

CellLagCorrelation cell_lag_correlation(const cv::Mat& plane, cv::Size cell) {
    if (cell.width < 2 || cell.height < 2)
        throw synth::SynthError("cell lag correlation needs cells of 2 px or more");
    const Autocorrelation auto_corr(plane);
    const int mx = plane.cols / 2, my = plane.rows / 2;
    CellLagCorrelation out;
    double whole = 0, half = 0;
    // Lags of (i, j) cells, j >= 0 (the other half-plane mirrors them), two cells or more away
    // (next to each other cells differ by construction), and the same half a cell further.
    for (int j = 0; (j + 1) * cell.height <= my; ++j)
        for (int i = -(mx / cell.width - 1); (i + 1) * cell.width <= mx; ++i) {
            if (std::max(std::abs(i), j) < 2 || (j == 0 && i < 0)) continue;
            whole += auto_corr.at(i * cell.width, j * cell.height);
            half +=
                auto_corr.at(i * cell.width + cell.width / 2, j * cell.height + cell.height / 2);
            ++out.lags;
        }
    if (out.lags > 0) out.whole_cells = whole / out.lags, out.half_cells = half / out.lags;
    return out;
}

}  // namespace tilejet::quality
