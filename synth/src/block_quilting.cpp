#include "block_quilting.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "tilejet/synth/error.hpp"

namespace tilejet::synth::detail {

namespace {

// On very large exemplars blocks come from a random window of this size: the best match among
// a million positions is as good as any for a cell image, and the search stays fast.
constexpr int kSearchWindow = 1024;

std::vector<int> block_starts(int length, int step) {
    const int n = std::max(2, int(std::lround(double(length) / step)));
    std::vector<int> starts(static_cast<size_t>(n) + 1);
    for (int k = 0; k <= n; ++k)
        starts[size_t(k)] = int(int64_t(k) * length / n);
    return starts;
}

float lab_sq(const cv::Vec3f& a, const cv::Vec3f& b) {
    const cv::Vec3f d = a - b;
    return d.dot(d);
}

// Minimum-cost path through a band of `cost` (rows x cols), one cell per row, moving at most
// one column between rows. Returns the column of the path in each row.
std::vector<int> min_path(const cv::Mat& cost) {
    const int rows = cost.rows, cols = cost.cols;
    cv::Mat acc = cost.clone();
    for (int y = 1; y < rows; ++y)
        for (int x = 0; x < cols; ++x) {
            float best = acc.at<float>(y - 1, x);
            if (x > 0) best = std::min(best, acc.at<float>(y - 1, x - 1));
            if (x + 1 < cols) best = std::min(best, acc.at<float>(y - 1, x + 1));
            acc.at<float>(y, x) += best;
        }
    std::vector<int> path(static_cast<size_t>(rows));
    int x = 0;
    for (int c = 1; c < cols; ++c)
        if (acc.at<float>(rows - 1, c) < acc.at<float>(rows - 1, x)) x = c;
    path[size_t(rows - 1)] = x;
    for (int y = rows - 2; y >= 0; --y) {
        int bx = x;
        for (int c = std::max(0, x - 1); c <= std::min(cols - 1, x + 1); ++c)
            if (acc.at<float>(y, c) < acc.at<float>(y, bx)) bx = c;
        path[size_t(y)] = x = bx;
    }
    return path;
}

struct Canvas {
    cv::Mat rgb, lab, filled;
    int wrap_x(int x) const { return ((x % rgb.cols) + rgb.cols) % rgb.cols; }
    int wrap_y(int y) const { return ((y % rgb.rows) + rgb.rows) % rgb.rows; }
};

// The placed strips a block must match: the overlap bands on each side that lie wholly on
// pixels already placed. Only these take part in the error and in the cut.
std::vector<cv::Rect> placed_strips(const cv::Mat& filled, int overlap) {
    const int bw = filled.cols, bh = filled.rows;
    std::vector<cv::Rect> strips;
    for (const cv::Rect r : {cv::Rect(0, 0, overlap, bh), cv::Rect(bw - overlap, 0, overlap, bh),
                             cv::Rect(0, 0, bw, overlap), cv::Rect(0, bh - overlap, bw, overlap)})
        if (cv::countNonZero(filled(r)) == r.area()) strips.push_back(r);
    return strips;
}

// Finds blocks of the exemplar that match a footprint's placed strips. The overlap error
// (sum of squared CIELab differences over the strips' pixels, m) is expanded as
//   sum m*I^2 - 2 sum (m*T)*I + sum m*T^2
// whose two position-dependent terms are correlations: with the exemplar's spectra computed
// once per quilt, each block costs four forward FFTs and one inverse (several times faster
// than cv::matchTemplate, which transforms the exemplar again on every call).
class BlockSearch {
  public:
    // The window searched is kSearchWindow px, or twice the largest footprint when that is
    // more (blocks of a slab scan's baseline quilt are 2048 px), within the exemplar.
    BlockSearch(const cv::Mat& ex_lab, Rng& rng, cv::Size largest) {
        window_ = cv::Rect(0, 0, ex_lab.cols, ex_lab.rows);
        const int wide = std::max(kSearchWindow, 2 * largest.width);
        const int high = std::max(kSearchWindow, 2 * largest.height);
        if (ex_lab.cols > wide) window_.x = rng.range(0, ex_lab.cols - wide), window_.width = wide;
        if (ex_lab.rows > high) window_.y = rng.range(0, ex_lab.rows - high), window_.height = high;
        size_ = {cv::getOptimalDFTSize(window_.width), cv::getOptimalDFTSize(window_.height)};
        std::vector<cv::Mat> channels;
        cv::split(ex_lab(window_), channels);
        cv::Mat energy(window_.size(), CV_32F, cv::Scalar(0));
        for (int c = 0; c < 3; ++c) {
            spectrum_[c] = forward(channels[size_t(c)]);
            energy += channels[size_t(c)].mul(channels[size_t(c)]);
        }
        energy_spectrum_ = forward(energy);
    }

    // `at` is where the block goes on the canvas: with a lattice, only exemplar positions a
    // lattice translation away from it are eligible.
    cv::Point choose(const cv::Mat& templ, const std::vector<cv::Rect>& strips, double tolerance,
                     cv::Point at, const LatticeTranslations* lattice, Rng& rng) const {
        const int range_x = window_.width - templ.cols, range_y = window_.height - templ.rows;
        auto allowed = [&](int x, int y) {
            return !lattice || lattice->allows(window_.tl() + cv::Point(x, y) - at);
        };
        if (strips.empty()) {
            for (int attempt = 0; attempt < 64; ++attempt) {
                cv::Point p(rng.range(0, range_x), rng.range(0, range_y));
                if (lattice)
                    p = lattice->near(cv::Point2d(p + window_.tl() - at), rng) + at - window_.tl();
                if (p.x >= 0 && p.y >= 0 && p.x <= range_x && p.y <= range_y)
                    return window_.tl() + p;
            }
            return window_.tl();
        }

        cv::Mat mask(templ.size(), CV_32F, cv::Scalar(0));
        for (const cv::Rect& s : strips)
            mask(s).setTo(1);
        std::vector<cv::Mat> t;
        cv::split(templ, t);
        double constant = 0;
        cv::Mat acc;
        cv::mulSpectrums(energy_spectrum_, forward(mask), acc, 0, true);
        for (int c = 0; c < 3; ++c) {
            const cv::Mat masked = t[size_t(c)].mul(mask);
            constant += masked.dot(t[size_t(c)]);
            cv::Mat cross;
            cv::mulSpectrums(spectrum_[c], forward(masked), cross, 0, true);
            acc -= 2 * cross;
        }
        cv::Mat error;
        cv::dft(acc, error, cv::DFT_INVERSE | cv::DFT_SCALE | cv::DFT_REAL_OUTPUT);
        error = error(cv::Rect(0, 0, range_x + 1, range_y + 1)) + constant;

        double best = -1;
        for (int y = 0; y < error.rows; ++y)
            for (int x = 0; x < error.cols; ++x)
                if (allowed(x, y) && (best < 0 || error.at<float>(y, x) < best))
                    best = error.at<float>(y, x);
        best = std::max(best, 0.0);  // rounding in the FFT can dip below zero
        const double limit = best * (1 + tolerance) + 1e-3;
        std::vector<cv::Point> eligible;
        for (int y = 0; y < error.rows; ++y)
            for (int x = 0; x < error.cols; ++x)
                if (error.at<float>(y, x) <= limit && allowed(x, y)) eligible.emplace_back(x, y);
        if (eligible.empty()) eligible.emplace_back(0, 0);
        return window_.tl() + eligible[size_t(rng.below(eligible.size()))];
    }

  private:
    cv::Mat forward(const cv::Mat& plane) const {
        cv::Mat padded(size_, CV_32F, cv::Scalar(0)), spectrum;
        plane.copyTo(padded(cv::Rect(0, 0, plane.cols, plane.rows)));
        cv::dft(padded, spectrum);
        return spectrum;
    }

    cv::Rect window_;
    cv::Size size_;
    cv::Mat spectrum_[3], energy_spectrum_;
};

// Quilts over a canvas of `size`; with `wrap` false the canvas is grown by one overlap to the
// left and top so that no footprint reaches round to the far side, and cropped afterwards.
cv::Mat quilt(const cv::Mat& ex_rgb, const cv::Mat& ex_lab, cv::Size size,
              const QuiltParams& params, Rng& rng, bool wrap) {
    const int o = params.overlap, step = params.block - params.overlap;
    // Each block must reach past its overlap strips, or a cut could not separate them.
    if (o < 1 || step <= o) throw SynthError("quilting block must be over twice its overlap");
    const std::vector<int> xs = block_starts(size.width, step),
                           ys = block_starts(size.height, step);
    const int largest_w = [&] {
        int m = 0;
        for (size_t k = 1; k < xs.size(); ++k)
            m = std::max(m, xs[k] - xs[k - 1]);
        return m + o;
    }();
    const int largest_h = [&] {
        int m = 0;
        for (size_t k = 1; k < ys.size(); ++k)
            m = std::max(m, ys[k] - ys[k - 1]);
        return m + o;
    }();
    if (largest_w > ex_rgb.cols || largest_h > ex_rgb.rows)
        throw SynthError("exemplar " + std::to_string(ex_rgb.cols) + "x" +
                         std::to_string(ex_rgb.rows) + " px is too small for quilting blocks of " +
                         std::to_string(params.block) + " px");

    const int margin = wrap ? 0 : o;
    const cv::Size canvas(size.width + margin, size.height + margin);
    Canvas c{cv::Mat(canvas, CV_8UC3, cv::Scalar::all(0)),
             cv::Mat(canvas, CV_32FC3, cv::Scalar::all(0)), cv::Mat(canvas, CV_8U, cv::Scalar(0))};

    const BlockSearch search(ex_lab, rng, {largest_w, largest_h});
    for (size_t l = 0; l + 1 < ys.size(); ++l) {
        for (size_t k = 0; k + 1 < xs.size(); ++k) {
            // Footprint: the block plus its overlap to the left and above, wrapping around.
            const int fx = xs[k] - o + margin, fy = ys[l] - o + margin;
            const int bw = xs[k + 1] - xs[k] + o, bh = ys[l + 1] - ys[l] + o;
            cv::Mat templ(bh, bw, CV_32FC3), mask(bh, bw, CV_8U);
            for (int y = 0; y < bh; ++y)
                for (int x = 0; x < bw; ++x) {
                    const int cy = c.wrap_y(fy + y), cx = c.wrap_x(fx + x);
                    templ.at<cv::Vec3f>(y, x) = c.lab.at<cv::Vec3f>(cy, cx);
                    mask.at<uint8_t>(y, x) = c.filled.at<uint8_t>(cy, cx) ? 255 : 0;
                }
            const std::vector<cv::Rect> strips = placed_strips(mask, o);
            const cv::Point at =
                search.choose(templ, strips, params.tolerance, {fx, fy}, params.lattice, rng);

            cv::Mat err(bh, bw, CV_32F, cv::Scalar(0));
            for (int y = 0; y < bh; ++y)
                for (int x = 0; x < bw; ++x)
                    if (mask.at<uint8_t>(y, x))
                        err.at<float>(y, x) = lab_sq(templ.at<cv::Vec3f>(y, x),
                                                     ex_lab.at<cv::Vec3f>(at.y + y, at.x + x));

            // Each placed strip is cut along its minimum-error path; the new block shows on
            // the inner side of every cut.
            cv::Mat take_new(bh, bw, CV_8U, cv::Scalar(1));
            for (const cv::Rect& s : strips) {
                const bool vertical = s.height == bh && s.width == o;
                const auto path = min_path(vertical ? cv::Mat(err(s)) : cv::Mat(err(s).t()));
                const bool near_side = vertical ? s.x == 0 : s.y == 0;
                for (int along = 0; along < (vertical ? bh : bw); ++along)
                    for (int across = 0; across < o; ++across) {
                        const int cut = path[size_t(along)];
                        if (near_side ? across >= cut : across <= cut) continue;
                        const int x = vertical ? s.x + across : along;
                        const int y = vertical ? along : s.y + across;
                        take_new.at<uint8_t>(y, x) = 0;
                    }
            }

            for (int y = 0; y < bh; ++y)
                for (int x = 0; x < bw; ++x) {
                    const int cy = c.wrap_y(fy + y), cx = c.wrap_x(fx + x);
                    if (c.filled.at<uint8_t>(cy, cx) && !take_new.at<uint8_t>(y, x)) continue;
                    c.rgb.at<cv::Vec3b>(cy, cx) = ex_rgb.at<cv::Vec3b>(at.y + y, at.x + x);
                    c.lab.at<cv::Vec3f>(cy, cx) = ex_lab.at<cv::Vec3f>(at.y + y, at.x + x);
                    c.filled.at<uint8_t>(cy, cx) = 1;
                }
        }
    }
    return wrap ? c.rgb : c.rgb(cv::Rect(margin, margin, size.width, size.height)).clone();
}

}  // namespace

cv::Mat quilt_toroidal(const cv::Mat& ex_rgb, const cv::Mat& ex_lab, cv::Size size,
                       const QuiltParams& params, Rng& rng) {
    return quilt(ex_rgb, ex_lab, size, params, rng, true);
}

cv::Mat quilt_open(const cv::Mat& ex_rgb, const cv::Mat& ex_lab, cv::Size size,
                   const QuiltParams& params, Rng& rng) {
    return quilt(ex_rgb, ex_lab, size, params, rng, false);
}

}  // namespace tilejet::synth::detail
