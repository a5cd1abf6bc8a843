#include "quilting.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "tilejet/synth/error.hpp"

namespace tilejet::synth::detail {

namespace {

// Block search on very large exemplars looks in a random window of this size: the best match
// in a million positions is as good as any for a cell image, and the search stays fast.
constexpr int kSearchWindow = 1024;

std::vector<int> block_starts(int length, int step) {
    const int n = std::max(2, int(std::lround(double(length) / step)));
    std::vector<int> starts(static_cast<size_t>(n) + 1);
    for (int k = 0; k <= n; ++k) starts[size_t(k)] = int(int64_t(k) * length / n);
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

cv::Point choose_block(const cv::Mat& ex_lab, const cv::Mat& templ, const cv::Mat& mask,
                       double tolerance, Rng& rng) {
    const int range_x = ex_lab.cols - templ.cols, range_y = ex_lab.rows - templ.rows;
    if (cv::countNonZero(mask) == 0) return {rng.range(0, range_x), rng.range(0, range_y)};

    cv::Rect window(0, 0, ex_lab.cols, ex_lab.rows);
    if (ex_lab.cols > kSearchWindow + templ.cols)
        window.x = rng.range(0, ex_lab.cols - kSearchWindow - templ.cols),
        window.width = kSearchWindow + templ.cols;
    if (ex_lab.rows > kSearchWindow + templ.rows)
        window.y = rng.range(0, ex_lab.rows - kSearchWindow - templ.rows),
        window.height = kSearchWindow + templ.rows;

    cv::Mat error;
    cv::matchTemplate(ex_lab(window), templ, error, cv::TM_SQDIFF, mask);
    double best = 0;
    cv::minMaxLoc(error, &best);
    best = std::max(best, 0.0);  // the FFT path can return tiny negatives
    const double limit = best * (1 + tolerance) + 1e-6;
    std::vector<cv::Point> eligible;
    for (int y = 0; y < error.rows; ++y)
        for (int x = 0; x < error.cols; ++x)
            if (error.at<float>(y, x) <= limit) eligible.emplace_back(x, y);
    const cv::Point pick = eligible[size_t(rng.below(eligible.size()))];
    return pick + window.tl();
}

}  // namespace

cv::Mat quilt_toroidal(const cv::Mat& ex_rgb, const cv::Mat& ex_lab, cv::Size size,
                       const QuiltParams& params, Rng& rng) {
    const int o = params.overlap, step = params.block - params.overlap;
    // Each block must reach past its overlap strips, or a cut could not separate them.
    if (o < 1 || step <= o) throw SynthError("quilting block must be over twice its overlap");
    const std::vector<int> xs = block_starts(size.width, step), ys = block_starts(size.height, step);
    const int largest_w = [&] {
        int m = 0;
        for (size_t k = 1; k < xs.size(); ++k) m = std::max(m, xs[k] - xs[k - 1]);
        return m + o;
    }();
    const int largest_h = [&] {
        int m = 0;
        for (size_t k = 1; k < ys.size(); ++k) m = std::max(m, ys[k] - ys[k - 1]);
        return m + o;
    }();
    if (largest_w > ex_rgb.cols || largest_h > ex_rgb.rows)
        throw SynthError("exemplar " + std::to_string(ex_rgb.cols) + "x" +
                         std::to_string(ex_rgb.rows) + " px is too small for quilting blocks of " +
                         std::to_string(params.block) + " px");

    Canvas c{cv::Mat(size, CV_8UC3, cv::Scalar::all(0)), cv::Mat(size, CV_32FC3, cv::Scalar::all(0)),
             cv::Mat(size, CV_8U, cv::Scalar(0))};

    for (size_t l = 0; l + 1 < ys.size(); ++l) {
        for (size_t k = 0; k + 1 < xs.size(); ++k) {
            // Footprint: the block plus its overlap to the left and above, wrapping around.
            const int fx = xs[k] - o, fy = ys[l] - o;
            const int bw = xs[k + 1] - xs[k] + o, bh = ys[l + 1] - ys[l] + o;
            cv::Mat templ(bh, bw, CV_32FC3), mask(bh, bw, CV_8U);
            for (int y = 0; y < bh; ++y)
                for (int x = 0; x < bw; ++x) {
                    const int cy = c.wrap_y(fy + y), cx = c.wrap_x(fx + x);
                    templ.at<cv::Vec3f>(y, x) = c.lab.at<cv::Vec3f>(cy, cx);
                    mask.at<uint8_t>(y, x) = c.filled.at<uint8_t>(cy, cx) ? 255 : 0;
                }
            const cv::Point at = choose_block(ex_lab, templ, mask, params.tolerance, rng);

            cv::Mat err(bh, bw, CV_32F, cv::Scalar(0));
            for (int y = 0; y < bh; ++y)
                for (int x = 0; x < bw; ++x)
                    if (mask.at<uint8_t>(y, x))
                        err.at<float>(y, x) = lab_sq(templ.at<cv::Vec3f>(y, x),
                                                     ex_lab.at<cv::Vec3f>(at.y + y, at.x + x));

            // A strip takes part in the cut only when it lies wholly on placed pixels.
            auto all_filled = [&](cv::Rect r) { return cv::countNonZero(mask(r)) == r.area(); };
            const cv::Rect left(0, 0, o, bh), right(bw - o, 0, o, bh);
            const cv::Rect top(0, 0, bw, o), bottom(0, bh - o, bw, o);
            cv::Mat take_new(bh, bw, CV_8U, cv::Scalar(1));
            if (all_filled(left)) {
                const auto path = min_path(err(left));
                for (int y = 0; y < bh; ++y)
                    for (int x = 0; x < path[size_t(y)]; ++x) take_new.at<uint8_t>(y, x) = 0;
            }
            if (all_filled(right)) {
                const auto path = min_path(err(right));
                for (int y = 0; y < bh; ++y)
                    for (int x = bw - o + path[size_t(y)] + 1; x < bw; ++x)
                        take_new.at<uint8_t>(y, x) = 0;
            }
            if (all_filled(top)) {
                const auto path = min_path(cv::Mat(err(top).t()));
                for (int x = 0; x < bw; ++x)
                    for (int y = 0; y < path[size_t(x)]; ++y) take_new.at<uint8_t>(y, x) = 0;
            }
            if (all_filled(bottom)) {
                const auto path = min_path(cv::Mat(err(bottom).t()));
                for (int x = 0; x < bw; ++x)
                    for (int y = bh - o + path[size_t(x)] + 1; y < bh; ++y)
                        take_new.at<uint8_t>(y, x) = 0;
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
    return c.rgb;
}

}  // namespace tilejet::synth::detail
