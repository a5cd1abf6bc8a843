#include "offset_matching.hpp"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace tilejet::synth::detail {

std::vector<cv::Point> ranked_offsets(const OffsetSearch& search, const cv::Mat& old_lab,
                                      const cv::Mat& mask, Rng& rng, size_t count) {
    if (search.source_lab.cols < old_lab.cols || search.source_lab.rows < old_lab.rows) return {};
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
    cv::Mat costs;  // (W - w + 1) x (H - h + 1), CV_32F
    cv::matchTemplate(src, old_lab, costs, cv::TM_SQDIFF, mask);
    if (search.add_penalty) search.add_penalty(area, costs);
    std::vector<std::pair<float, cv::Point>> ranked;
    ranked.reserve(costs.total());
    for (int y = 0; y < costs.rows; ++y)
        for (int x = 0; x < costs.cols; ++x) {
            const cv::Point at = cv::Point(x, y) + area.tl();
            if (search.allowed && !search.allowed(at)) continue;
            ranked.push_back({costs.at<float>(y, x), at});
        }
    if (ranked.empty()) return {};
    // Only the best few matter: a partial sort of the best slice, widened while the distinct
    // places found do not reach `count` (they rarely need more than a few hundred positions).
    const auto by_cost = [](const auto& a, const auto& b) {
        return a.first < b.first ||
               (a.first == b.first &&
                (a.second.y < b.second.y || (a.second.y == b.second.y && a.second.x < b.second.x)));
    };
    std::vector<cv::Point> distinct;
    size_t sorted = 0;
    for (size_t slice = 256;; slice *= 4) {
        const size_t end = std::min(slice, ranked.size());
        std::partial_sort(ranked.begin() + ptrdiff_t(sorted), ranked.begin() + ptrdiff_t(end),
                          ranked.end(), by_cost);
        for (size_t i = sorted; i < end && distinct.size() < count; ++i) {
            const cv::Point at = ranked[i].second;
            bool apart = true;
            for (const cv::Point& d : distinct)
                apart =
                    apart && std::max(std::abs(d.x - at.x), std::abs(d.y - at.y)) >= search.spread;
            if (apart) distinct.push_back(at);
        }
        sorted = end;
        if (distinct.size() >= count || end == ranked.size()) break;
    }
    return distinct;
}

}  // namespace tilejet::synth::detail
