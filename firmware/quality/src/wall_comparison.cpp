#include "tilejet/quality/wall_comparison.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "tilejet/quality/quality_report.hpp"

namespace tilejet::quality {

namespace {

constexpr int kGap = 24;    // white between two walls, so no wall seems to continue the next
constexpr int kLabel = 40;  // the band above each wall that names it

}  // namespace

cv::Mat wall_corner(const Wall& wall, int side) {
    const int columns = std::min(side, wall.columns), rows = std::min(side, wall.rows());
    return wall.laid(cv::Rect(0, 0, columns * wall.tile.width, rows * wall.tile.height));
}

double write_walls_side_by_side(const std::vector<NamedPicture>& walls,
                                const std::filesystem::path& dir, int max_side) {
    if (walls.empty()) throw std::invalid_argument("no walls to compare");
    int largest = 1;
    for (const NamedPicture& w : walls) {
        write_rgb_png(w.rgb, dir / ("wall3x3-" + w.name + ".png"));
        largest = std::max({largest, w.rgb.cols, w.rgb.rows});
    }
    // One factor for all: the point is to compare them at the same scale.
    const double scale = std::min(1.0, double(max_side) / largest);
    std::vector<cv::Mat> scaled;
    int width = kGap, height = 0;
    for (const NamedPicture& w : walls) {
        cv::Mat s;
        const cv::Size size(std::max(1, int(std::lround(w.rgb.cols * scale))),
                            std::max(1, int(std::lround(w.rgb.rows * scale))));
        cv::resize(w.rgb, s, size, 0, 0, cv::INTER_AREA);
        width += s.cols + kGap;
        height = std::max(height, s.rows);
        scaled.push_back(s);
    }
    cv::Mat out(kLabel + height + kGap, width, CV_8UC3, cv::Scalar::all(255));
    int x = kGap;
    for (size_t k = 0; k < walls.size(); ++k) {
        cv::putText(out, walls[k].name, cv::Point(x, kLabel - 12), cv::FONT_HERSHEY_SIMPLEX, 0.9,
                    cv::Scalar::all(40), 2, cv::LINE_AA);
        scaled[k].copyTo(out(cv::Rect(x, kLabel, scaled[k].cols, scaled[k].rows)));
        x += scaled[k].cols + kGap;
    }
    write_rgb_png(out, dir / "walls-side-by-side.png");
    return scale;
}

}  // namespace tilejet::quality
