#include "offset_matching.hpp"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <vector>

namespace tilejet::synth::detail {

std::optional<cv::Point> match_offset(const OffsetSearch& search, const cv::Mat& old_lab,
                                      const cv::Mat& mask, Rng& rng) {
    if (search.source_lab.cols < old_lab.cols || search.source_lab.rows < old_lab.rows)
        return std::nullopt;
    cv::Rect area(0, 0, search.source_lab.cols, search.source_lab.rows);
    const int across = area.width - old_lab.cols + 1, down = area.height - old_lab.rows + 1;
    if (search.window > 0 && across > search.window) {
        area.x = rng.range(0, across - search.window);
        area.width = search.window + old_lab.cols - 1;
    }
    if (search.window > 0 && down > search.window) {
        area.y = rng.range(0, down - search.window);
        area.height = search.window + old_lab.rows - 1;
    }
    const cv::Mat src = search.source_lab(area);
    const auto allowed = [&](cv::Point at) {
        return !search.allowed || search.allowed(at + area.tl());
    };
    cv::Mat costs;  // (W - w + 1) x (H - h + 1), CV_32F
    cv::matchTemplate(src, old_lab, costs, cv::TM_SQDIFF, mask);
    float best = std::numeric_limits<float>::max();
    for (int y = 0; y < costs.rows; ++y)
        for (int x = 0; x < costs.cols; ++x)
            if (costs.at<float>(y, x) < best && allowed({x, y})) best = costs.at<float>(y, x);
    if (best == std::numeric_limits<float>::max()) return std::nullopt;
    // The FFT leaves rounding noise around zero; a floor keeps "within 10%" meaningful there.
    const float limit = best * float(1 + search.tolerance) + 1e-3f * float(cv::sum(mask)[0]);
    std::vector<std::pair<float, cv::Point>> ranked;
    for (int y = 0; y < costs.rows; ++y)
        for (int x = 0; x < costs.cols; ++x)
            if (allowed({x, y}))
                ranked.push_back({costs.at<float>(y, x), cv::Point(x, y) + area.tl()});
    // Stable: equal costs keep raster order, so the pick never depends on the sort.
    std::stable_sort(ranked.begin(), ranked.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<cv::Point> near, distinct;
    for (const auto& [cost, at] : ranked) {
        const bool within = cost <= limit;
        if (!within && int(distinct.size()) >= search.min_choices) break;
        bool apart = true;
        for (const cv::Point& d : distinct)
            apart = apart && std::max(std::abs(d.x - at.x), std::abs(d.y - at.y)) >= search.spread;
        if (apart) distinct.push_back(at);
        if (within) near.push_back(at);
    }
    if (int(distinct.size()) > int(near.size()) || near.empty()) near = distinct;
    return near[size_t(rng.below(near.size()))];
}

}  // namespace tilejet::synth::detail
