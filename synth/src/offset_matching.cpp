#include "offset_matching.hpp"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace tilejet::synth::detail {

namespace {

// Coarse places looked at round, at full resolution, per offset asked for: the coarse match
// is blurred, and its best place is not always the best one at full resolution.
constexpr size_t kCoarsePlacesPerOffset = 2;
// The coarse piece must keep this many px a side, or its match says little.
constexpr int kCoarsePieceMin = 8;
// The coarse-to-fine search's places join the random window's only where its best match costs
// under this share of the window's best: a rescue where the window holds nothing that fits.
// Always joining (or searching coarse to fine alone), blocks drifted to the source's few calm
// places, and the set showed less of the stone: an 8192 px slab's texture energy 2.73-2.96
// times quilting's against 2.40 with random windows alone; at a half, one place won again and
// again and its wall showed a grid of dots. At a quarter, 9 of 72 blocks of that slab were
// rescued, its white shards were gone and its texture energy 2.32.
constexpr float kRescue = 0.25f;

using Ranked = std::vector<std::pair<float, cv::Point>>;

// Appends each allowed position of the window at `area` (the positions whose piece lies in
// it) with its match cost plus the penalty.
void rank_area(const OffsetSearch& search, const cv::Rect& area, const cv::Mat& old_lab,
               const cv::Mat& mask, Ranked& ranked) {
    cv::Mat costs;  // (W - w + 1) x (H - h + 1), CV_32F
    cv::matchTemplate(search.source_lab(area), old_lab, costs, cv::TM_SQDIFF, mask);
    if (search.add_penalty) search.add_penalty(area, costs);
    ranked.reserve(ranked.size() + costs.total());
    for (int y = 0; y < costs.rows; ++y)
        for (int x = 0; x < costs.cols; ++x) {
            const cv::Point at = cv::Point(x, y) + area.tl();
            if (search.allowed && !search.allowed(at)) continue;
            ranked.push_back({costs.at<float>(y, x), at});
        }
}

bool by_cost(const std::pair<float, cv::Point>& a, const std::pair<float, cv::Point>& b) {
    return a.first < b.first ||
           (a.first == b.first &&
            (a.second.y < b.second.y || (a.second.y == b.second.y && a.second.x < b.second.x)));
}

// Up to `count` positions of `ranked`, best first, each `spread` or more (Chebyshev) from
// those before it. Only the best few matter: a partial sort of the best slice, widened while
// the distinct places found do not reach `count` (they rarely need more than a few hundred).
std::vector<cv::Point> distinct_best(Ranked& ranked, size_t count, int spread) {
    std::vector<cv::Point> distinct;
    size_t sorted = 0;
    for (size_t slice = 256; !ranked.empty(); slice *= 4) {
        const size_t end = std::min(slice, ranked.size());
        std::partial_sort(ranked.begin() + ptrdiff_t(sorted), ranked.begin() + ptrdiff_t(end),
                          ranked.end(), by_cost);
        for (size_t i = sorted; i < end && distinct.size() < count; ++i) {
            const cv::Point at = ranked[i].second;
            bool apart = true;
            for (const cv::Point& d : distinct)
                apart = apart && std::max(std::abs(d.x - at.x), std::abs(d.y - at.y)) >= spread;
            if (apart) distinct.push_back(at);
        }
        sorted = end;
        if (distinct.size() >= count || end == ranked.size()) break;
    }
    return distinct;
}

float best_cost(const Ranked& ranked) {
    return std::ranges::min_element(ranked, by_cost)->first;
}

// The positions round the best places of the whole coarse source, with their full match costs.
Ranked coarse_to_fine(const OffsetSearch& search, const cv::Mat& old_lab, const cv::Mat& mask,
                      size_t count) {
    const int f = search.coarse_factor;
    const int across = search.source_lab.cols - old_lab.cols + 1,
              down = search.source_lab.rows - old_lab.rows + 1;
    const cv::Mat old_small = coarse_source(old_lab, f), mask_small = coarse_source(mask, f);
    Ranked places, fine;
    rank_area(OffsetSearch{*search.coarse, {}, 1, 0, {}, nullptr, 1},
              cv::Rect({0, 0}, search.coarse->size()), old_small, mask_small, places);
    const int coarse_spread = std::max(2, (search.spread + f - 1) / f);
    for (const cv::Point place :
         distinct_best(places, kCoarsePlacesPerOffset * count + 2, coarse_spread)) {
        // The full-resolution positions this coarse place stands for, and a coarse pixel round
        // them (the coarse match is off by up to one).
        const int x0 = std::clamp(place.x * f - f, 0, across - 1),
                  x1 = std::clamp(place.x * f + 2 * f - 1, 0, across - 1);
        const int y0 = std::clamp(place.y * f - f, 0, down - 1),
                  y1 = std::clamp(place.y * f + 2 * f - 1, 0, down - 1);
        rank_area(search, cv::Rect(x0, y0, x1 - x0 + old_lab.cols, y1 - y0 + old_lab.rows), old_lab,
                  mask, fine);
    }
    return fine;
}

}  // namespace

cv::Mat coarse_source(const cv::Mat& image, int factor) {
    const cv::Size small(image.cols / factor, image.rows / factor);
    cv::Mat coarse;
    cv::resize(image(cv::Rect({0, 0}, small * factor)), coarse, small, 0, 0, cv::INTER_AREA);
    return coarse;
}

bool searches_coarse_to_fine(const OffsetSearch& search, cv::Size piece) {
    // A whole search (window 0) needs no other.
    if (!search.coarse || search.coarse_factor < 2 || search.window <= 0) return false;
    if (piece.width / search.coarse_factor < kCoarsePieceMin ||
        piece.height / search.coarse_factor < kCoarsePieceMin)
        return false;
    return search.source_lab.cols - piece.width + 1 > search.window ||
           search.source_lab.rows - piece.height + 1 > search.window;
}

std::vector<cv::Point> ranked_offsets(const OffsetSearch& search, const cv::Mat& old_lab,
                                      const cv::Mat& mask, Rng& rng, size_t count) {
    if (search.source_lab.cols < old_lab.cols || search.source_lab.rows < old_lab.rows) return {};
    const int across = search.source_lab.cols - old_lab.cols + 1,
              down = search.source_lab.rows - old_lab.rows + 1;
    cv::Rect area(0, 0, search.source_lab.cols, search.source_lab.rows);
    if (search.window > 0 && across > search.window) {
        area.x = rng.range(0, across - search.window);
        area.width = search.window + old_lab.cols - 1;
    }
    if (search.window > 0 && down > search.window) {
        area.y = rng.range(0, down - search.window);
        area.height = search.window + old_lab.rows - 1;
    }
    Ranked ranked;
    rank_area(search, area, old_lab, mask, ranked);
    if (searches_coarse_to_fine(search, old_lab.size())) {
        Ranked rescue = coarse_to_fine(search, old_lab, mask, count);
        if (!rescue.empty() && (ranked.empty() || best_cost(rescue) < kRescue * best_cost(ranked)))
            ranked.insert(ranked.end(), rescue.begin(), rescue.end());
    }
    return distinct_best(ranked, count, search.spread);
}

}  // namespace tilejet::synth::detail
