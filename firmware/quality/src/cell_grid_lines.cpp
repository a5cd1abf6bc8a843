#include "tilejet/quality/cell_grid_lines.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "tilejet/synth/error.hpp"
#include "tilejet/synth/internal/lab.hpp"

namespace tilejet::quality {

namespace {

// A span unrelated to the cell's: no small multiple of it comes within a few px of one of the
// cell's over a plane of eight cells.
constexpr double kUnrelatedSpan = 0.77;
// Places of the fold taken together: a seam wanders a few px along a border.
constexpr int kPlaceWidth = 5;

// The size of the tone change from `a` to its neighbour `b` (ΔE76 of the blurred tone).
double tone_step(const cv::Vec3f& a, const cv::Vec3f& b) {
    const cv::Vec3f d = b - a;
    return std::sqrt(double(d.dot(d)));
}

// The size of the tone change across each gap between neighbours along `profile`'s axis,
// averaged across it: index y is the gap between row y and y + 1.
std::vector<double> tone_changes(const cv::Mat& blurred, bool between_rows) {
    const int n = between_rows ? blurred.rows - 1 : blurred.cols - 1;
    std::vector<double> change(size_t(std::max(0, n)), 0.0);
    for (int y = 0; y + (between_rows ? 1 : 0) < blurred.rows; ++y) {
        const cv::Vec3f* row = blurred.ptr<cv::Vec3f>(y);
        const cv::Vec3f* below = between_rows ? blurred.ptr<cv::Vec3f>(y + 1) : nullptr;
        for (int x = 0; x + (between_rows ? 0 : 1) < blurred.cols; ++x) {
            change[size_t(between_rows ? y : x)] +=
                tone_step(row[x], between_rows ? below[x] : row[x + 1]);
        }
    }
    return change;
}

// The strongest place of `change` folded by `period` (smoothed over kPlaceWidth places, the
// fold wrapping round) against the median place, and where it lies.
std::pair<double, int> strongest_place(const std::vector<double>& change, double period) {
    const int places = std::max(1, int(std::lround(period)));
    std::vector<double> sum(size_t(places), 0.0), count(size_t(places), 0.0);
    for (size_t i = 0; i < change.size(); ++i) {
        // The gap after pixel i lies at i + 1/2; its place in the period, rounded down.
        const auto place = size_t(std::fmod(double(i) + 0.5, period) * places / period);
        sum[std::min(place, size_t(places - 1))] += change[i];
        count[std::min(place, size_t(places - 1))] += 1;
    }
    std::vector<double> fold(size_t(places), 0.0);
    for (int p = 0; p < places; ++p) {
        double s = 0, c = 0;
        for (int d = -kPlaceWidth / 2; d <= kPlaceWidth / 2; ++d) {
            const auto q = size_t(((p + d) % places + places) % places);
            s += sum[q], c += count[q];
        }
        fold[size_t(p)] = c > 0 ? s / c : 0;
    }
    std::vector<double> sorted = fold;
    std::nth_element(sorted.begin(), sorted.begin() + ptrdiff_t(sorted.size() / 2), sorted.end());
    const double median = sorted[sorted.size() / 2];
    const auto strongest = std::max_element(fold.begin(), fold.end());
    return {median > 0 ? *strongest / median : 1.0, int(strongest - fold.begin())};
}

// `plane` in CIELab, blurred to a fortieth of the cell: the tone a person sees from a few steps
// back. Refuses what cell_grid_lines() cannot measure.
cv::Mat blurred_tone(const cv::Mat& plane, cv::Size cell) {
    if (cell.width < 2 || cell.height < 2 || plane.type() != CV_8UC3 ||
        plane.cols < 2 * cell.width || plane.rows < 2 * cell.height)
        throw synth::SynthError(
            "cell grid lines need cells of 2 px or more and an 8-bit R,G,B plane of two cells "
            "each way");
    const double sigma = std::max(1.0, std::min(cell.width, cell.height) / 40.0);
    cv::Mat blurred;
    cv::GaussianBlur(synth::detail::to_lab(plane), blurred, {0, 0}, sigma, sigma,
                     cv::BORDER_REFLECT);
    return blurred;
}

// The size of the tone change between each pixel and its neighbour to the right (or below),
// averaged over the whole cells of `blurred` at each place of the cell, over its median.
cv::Mat folded_changes(const cv::Mat& blurred, cv::Size cell, bool between_rows) {
    cv::Mat sum(cell, CV_64F, cv::Scalar(0)), count(cell, CV_64F, cv::Scalar(0));
    const int rows = blurred.rows / cell.height * cell.height - (between_rows ? 1 : 0);
    const int cols = blurred.cols / cell.width * cell.width - (between_rows ? 0 : 1);
    for (int y = 0; y < rows; ++y) {
        const cv::Vec3f* row = blurred.ptr<cv::Vec3f>(y);
        const cv::Vec3f* next = between_rows ? blurred.ptr<cv::Vec3f>(y + 1) : row + 1;
        double* s = sum.ptr<double>(y % cell.height);
        double* c = count.ptr<double>(y % cell.height);
        for (int x = 0; x < cols; ++x) {
            s[x % cell.width] += tone_step(row[x], next[x]);
            c[x % cell.width] += 1;
        }
    }
    cv::Mat mean = sum / cv::max(count, 1.0);
    std::vector<double> sorted(mean.begin<double>(), mean.end<double>());
    std::nth_element(sorted.begin(), sorted.begin() + ptrdiff_t(sorted.size() / 2), sorted.end());
    const double median = sorted[sorted.size() / 2];
    return median > 0 ? cv::Mat(mean / median) : mean;
}

// cell_grid_lines()'s picture of `blurred` (blurred_tone()).
cv::Mat lines_picture(const cv::Mat& blurred, cv::Size cell) {
    // Nearest-neighbour enlarged to 256 px or more a panel, so small cells can be seen.
    const int scale = std::max(
        1, (256 + std::min(cell.width, cell.height) - 1) / std::min(cell.width, cell.height));
    constexpr int kGap = 8;
    const cv::Size panel(cell.width * scale, cell.height * scale);
    cv::Mat picture(panel.height, 2 * panel.width + kGap, CV_8UC3, cv::Scalar::all(255));
    for (const bool between_rows : {false, true}) {
        const cv::Mat ratio = folded_changes(blurred, cell, between_rows);
        // Half the median (blue) to twice it (red) on a log scale, the median in the middle.
        cv::Mat log_ratio, level;
        cv::log(cv::max(ratio, 1e-6), log_ratio);
        log_ratio.convertTo(level, CV_8U, 127.5 / std::log(2.0), 127.5);
        cv::Mat bgr, rgb;
        cv::applyColorMap(level, bgr, cv::COLORMAP_JET);
        cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
        cv::resize(
            rgb,
            picture(cv::Rect(between_rows ? panel.width + kGap : 0, 0, panel.width, panel.height)),
            panel, 0, 0, cv::INTER_NEAREST);
    }
    return picture;
}

}  // namespace

CellGridLines cell_grid_lines(const cv::Mat& plane, cv::Size cell, cv::Mat* picture) {
    const cv::Mat blurred = blurred_tone(plane, cell);
    if (picture) *picture = lines_picture(blurred, cell);
    CellGridLines lines;
    const auto measure = [&](bool between_rows, int side, double& ratio, int& at) {
        const std::vector<double> change = tone_changes(blurred, between_rows);
        const auto [on_cells, place] = strongest_place(change, side);
        const double own = strongest_place(change, side * kUnrelatedSpan).first;
        ratio = own > 0 ? on_cells / own : on_cells;
        at = place;
    };
    measure(true, cell.height, lines.rows, lines.row_at);
    measure(false, cell.width, lines.columns, lines.column_at);
    return lines;
}

}  // namespace tilejet::quality
