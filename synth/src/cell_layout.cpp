#include "cell_layout.hpp"

#include <algorithm>

namespace tilejet::synth::detail {

namespace {

// Knots of a wandering depth: about this many along an edge. With 2, 3 and 5 waves an edge (a
// sketch with sines, session 32) a 256 px cell's cut wandered enough that no place of the cell
// held it more than others; with knots every sixth of the edge, the same.
constexpr int kKnotsAlongEdge = 6;

// Depths along an edge of `length` px: random depths at the knots, joined by smoothsteps, at
// least `corner_least` within `corner_reach` of either end.
std::vector<int> wandering_depths(int length, const KeptDepths& d, Rng& rng) {
    const int spacing = std::max(8, length / kKnotsAlongEdge);
    const int knots = length / spacing + 2;
    std::vector<int> at(static_cast<size_t>(knots), 0);
    for (int& k : at)
        k = rng.range(d.least, std::max(d.least, d.most));
    std::vector<int> depth(static_cast<size_t>(length), 0);
    for (int t = 0; t < length; ++t) {
        const int k = t / spacing;
        // smoothstep 3u^2 - 2u^3 in 1/2^16ths of the step, integers only.
        const int64_t u = (int64_t(t - k * spacing) << 16) / spacing;
        const int64_t s = (3 * u * u * 65536 - 2 * u * u * u) >> 32;
        const int a = at[size_t(k)], b = at[size_t(k + 1)];
        int v = a + int(((b - a) * s + (1 << 15)) >> 16);
        if (t < d.corner_reach || t >= length - d.corner_reach) v = std::max(v, d.corner_least);
        depth[size_t(t)] = v;
    }
    return depth;
}

}  // namespace

KeptFrame kept_frame(cv::Size cell, const KeptDepths& d, Rng& rng) {
    KeptFrame f;
    f.top = wandering_depths(cell.width, d, rng);
    f.bottom = wandering_depths(cell.width, d, rng);
    f.left = wandering_depths(cell.height, d, rng);
    f.right = wandering_depths(cell.height, d, rng);
    return f;
}

std::vector<std::pair<int, int>> block_spans(int begin, int end, int block, int overlap) {
    const int length = end - begin;
    if (block >= length) return {{begin, end}};
    const int count = std::max(1, (length - overlap + (block - overlap) - 1) / (block - overlap));
    std::vector<std::pair<int, int>> spans;
    for (int i = 0; i < count; ++i)
        spans.push_back({begin + int(int64_t(length - overlap) * i / count),
                         begin + int(int64_t(length - overlap) * (i + 1) / count) + overlap});
    return spans;
}

std::vector<std::pair<int, int>> jittered_spans(std::vector<std::pair<int, int>> spans, int reach,
                                                Rng& rng) {
    for (size_t i = 1; i < spans.size(); ++i) {
        // Moving span i's start and span i-1's end together keeps their overlap; a span keeps
        // at least its overlap plus one pixel of its own.
        const int overlap = spans[i - 1].second - spans[i].first;
        const int low = std::max(-reach, spans[i - 1].first + overlap + 1 - spans[i].first);
        const int high = std::min(reach, spans[i].second - overlap - 1 - spans[i].first);
        if (low > high) continue;
        const int d = rng.range(low, high);
        spans[i].first += d, spans[i - 1].second += d;
    }
    return spans;
}

}  // namespace tilejet::synth::detail
