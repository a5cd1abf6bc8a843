#include "tilejet/quality/cell_place_tails.hpp"

#include <algorithm>

#include "tilejet/synth/error.hpp"
#include "tilejet/synth/internal/lab.hpp"

namespace tilejet::quality {

CellPlaceTails cell_place_tails(const cv::Mat& plane, cv::Size cell, double light, double dark) {
    if (cell.width < 1 || cell.height < 1 || plane.empty() || plane.type() != CV_8UC3)
        throw synth::SynthError("cell place tails need cells and an 8-bit R,G,B plane");
    CellPlaceTails r;
    r.band = std::max(1, std::min(cell.width, cell.height) / 10);
    const cv::Mat lab = synth::detail::to_lab(plane);
    double border = 0, inside = 0;
    for (int y = 0; y < lab.rows; ++y) {
        const cv::Vec3f* row = lab.ptr<cv::Vec3f>(y);
        const int v = y % cell.height;
        for (int x = 0; x < lab.cols; ++x) {
            const int u = x % cell.width;
            const bool at_border =
                std::min({u, v, cell.width - 1 - u, cell.height - 1 - v}) < r.band;
            const float l = row[x][0];
            (at_border ? border : inside) += 1;
            (at_border ? r.border_light : r.inside_light) += l > light;
            (at_border ? r.border_dark : r.inside_dark) += l < dark;
        }
    }
    if (border > 0) r.border_light /= border, r.border_dark /= border;
    if (inside > 0) r.inside_light /= inside, r.inside_dark /= inside;
    return r;
}

CellPlaceTails cell_place_tails(const cv::Mat& plane, cv::Size cell) {
    if (plane.empty() || plane.type() != CV_8UC3)
        throw synth::SynthError("cell place tails need an 8-bit R,G,B plane");
    const LabStatistics own = lab_statistics({plane}, 1);
    return cell_place_tails(plane, cell, lightness_quantile(own, 1 - kTailShare),
                            lightness_quantile(own, kTailShare));
}

}  // namespace tilejet::quality
