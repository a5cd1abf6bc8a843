#include "tilejet/quality/seam.hpp"

#include <cmath>

#include "tilejet/colour/statistics.hpp"
#include "tilejet/synth/internal/lab.hpp"
#include "tilejet/synth/internal/parallel_for.hpp"

namespace tilejet::quality {

namespace {

float step(const cv::Vec3f& a, const cv::Vec3f& b) {
    const cv::Vec3f d = a - b;
    return std::sqrt(d.dot(d));
}

StepStats stats_of(std::vector<float>& steps) {
    const colour::Summary s = colour::summarize(steps, 0.99);
    return {s.mean, s.percentile, s.count};
}

// Steps between the neighbour pairs whose bits are set in `seams` (all pairs if empty).
void collect_steps(const cv::Mat& rgb, const cv::Mat& seams, std::vector<float>& out) {
    const cv::Mat lab = synth::detail::to_lab(rgb);
    for (int y = 0; y < lab.rows; ++y) {
        const cv::Vec3f* row = lab.ptr<cv::Vec3f>(y);
        const cv::Vec3f* below = y + 1 < lab.rows ? lab.ptr<cv::Vec3f>(y + 1) : nullptr;
        const uint8_t* s = seams.empty() ? nullptr : seams.ptr<uint8_t>(y);
        for (int x = 0; x < lab.cols; ++x) {
            const uint8_t bits = s ? s[x] : (kSeamRight | kSeamBelow);
            if ((bits & kSeamRight) && x + 1 < lab.cols) out.push_back(step(row[x], row[x + 1]));
            if ((bits & kSeamBelow) && below) out.push_back(step(row[x], below[x]));
        }
    }
}

}  // namespace

StepStats neighbour_steps(const cv::Mat& rgb) {
    std::vector<float> steps;
    collect_steps(rgb, cv::Mat(), steps);
    return stats_of(steps);
}

SeamStats measure_seams(const Wall& wall, const StepStats& exemplar, int threads) {
    SeamStats out;
    if (wall.seams.size() != wall.tiles.size()) return out;
    for (const cv::Mat& s : wall.seams)
        if (s.empty()) return out;
    std::vector<std::vector<float>> per_tile(wall.tiles.size());
    synth::detail::parallel_for(wall.tiles.size(), threads, [&](size_t t) {
        collect_steps(wall.tiles[t], wall.seams[t], per_tile[t]);
    });
    std::vector<float> all;
    for (auto& v : per_tile)
        all.insert(all.end(), v.begin(), v.end()), v = {};
    out.known = true;
    out.seam = stats_of(all);
    const double pairs = double(wall.tiles.size()) *
                         double(2 * wall.tile.area() - wall.tile.width - wall.tile.height);
    out.seam_share = pairs > 0 ? double(out.seam.count) / pairs : 0;
    out.mean_ratio = exemplar.mean > 0 ? out.seam.mean / exemplar.mean : 0;
    out.p99_ratio = exemplar.p99 > 0 ? out.seam.p99 / exemplar.p99 : 0;
    return out;
}

}  // namespace tilejet::quality
