#include "graph_cut.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc/detail/gcgraph.hpp>

namespace tilejet::synth::detail {

namespace {

// |old - new| per pixel, row-major: CIELab CV_32FC3 images of one size.
std::vector<float> lab_difference(const cv::Mat& old_lab, const cv::Mat& new_lab) {
    CV_Assert(old_lab.type() == CV_32FC3 && new_lab.type() == CV_32FC3 &&
              old_lab.size() == new_lab.size());
    const int w = old_lab.cols, h = old_lab.rows;
    std::vector<float> diff(size_t(w) * size_t(h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const cv::Vec3f d = old_lab.at<cv::Vec3f>(y, x) - new_lab.at<cv::Vec3f>(y, x);
            diff[size_t(y) * size_t(w) + size_t(x)] = std::sqrt(d.dot(d));
        }
    return diff;
}

// The cost of the edge between neighbouring pixels a and b (graph_cut.hpp).
float edge_cost(const std::vector<float>& diff, size_t a, size_t b) {
    return diff[a] + diff[b] + kEdgeFloor;
}

// The cut's side of each pixel (1: new) on the full grid, every pixel a node.
std::vector<uint8_t> cut_whole(const std::vector<float>& diff, int w, int h,
                               const std::vector<Pin>& pins) {
    auto weight = [&](size_t a, size_t b) { return edge_cost(diff, a, b); };
    cv::detail::GCGraph<float> graph(unsigned(w * h), unsigned(4 * w * h));
    for (int i = 0; i < w * h; ++i)
        graph.addVtx();
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t n = size_t(y) * size_t(w) + size_t(x);
            if (x + 1 < w) {
                const float c = weight(n, n + 1);
                graph.addEdges(int(n), int(n + 1), c, c);
            }
            if (y + 1 < h) {
                const float c = weight(n, n + size_t(w));
                graph.addEdges(int(n), int(n + size_t(w)), c, c);
            }
            if (pins[n] == Pin::New) graph.addTermWeights(int(n), kForced, 0);
            if (pins[n] == Pin::Old) graph.addTermWeights(int(n), 0, kForced);
        }
    graph.maxFlow();
    std::vector<uint8_t> take_new(size_t(w) * size_t(h));
    for (size_t n = 0; n < take_new.size(); ++n)
        take_new[n] = graph.inSourceSegment(int(n)) ? 1 : 0;
    return take_new;
}

std::vector<uint8_t> cut_levels(const std::vector<float>& diff, int w, int h,
                                const std::vector<Pin>& pins);

// The multilevel banded cut (Lombaert et al. 2005): the cut of the window at half resolution,
// then the full-resolution cut within kBand coarse pixels of where that one runs, everything
// farther pinned to the side the coarse cut gave it. Max-flow grows with the area of the
// window; the band grows with the length of the seam.
std::vector<uint8_t> cut_banded(const std::vector<float>& diff, int w, int h,
                                const std::vector<Pin>& pins) {
    const int cw = (w + 1) / 2, ch = (h + 1) / 2;
    std::vector<float> coarse_diff(size_t(cw) * size_t(ch), 0);
    std::vector<Pin> coarse_pins(coarse_diff.size(), Pin::Free);
    for (int cy = 0; cy < ch; ++cy)
        for (int cx = 0; cx < cw; ++cx) {
            float lowest = std::numeric_limits<float>::max(), sum = 0;
            int count = 0;
            bool any_new = false, any_old = false;
            for (int y = 2 * cy; y < std::min(h, 2 * cy + 2); ++y)
                for (int x = 2 * cx; x < std::min(w, 2 * cx + 2); ++x) {
                    const size_t n = size_t(y) * size_t(w) + size_t(x);
                    lowest = std::min(lowest, diff[n]), sum += diff[n], ++count;
                    any_new |= pins[n] == Pin::New, any_old |= pins[n] == Pin::Old;
                }
            const size_t c = size_t(cy) * size_t(cw) + size_t(cx);
            // The mean of the four pulled half way to the least: a seam two pixels wide where
            // the images agree (a grout line, a vein's edge) stays a valley at half resolution,
            // where the mean alone would fill it in and the fine pass, kept near the coarse cut,
            // never see it; the least alone makes every coarse pixel look cheap, and patches
            // hugged their cores (coverage 14 % against 16 % on the demo design). Doubled: a
            // coarse pixel's edges stand for two fine edges each.
            coarse_diff[c] = lowest + sum / float(count);
            // Both sides pinned within one coarse pixel: the fine cut decides there.
            if (any_new != any_old) coarse_pins[c] = any_new ? Pin::New : Pin::Old;
        }
    const std::vector<uint8_t> coarse = cut_levels(coarse_diff, cw, ch, coarse_pins);

    // The band: coarse pixels within Chebyshev distance kBand of a coarse pixel on the other side.
    constexpr int kBand = 3;
    std::vector<uint8_t> near_cut(coarse.size(), 0);
    for (int cy = 0; cy < ch; ++cy)
        for (int cx = 0; cx < cw; ++cx) {
            const uint8_t side = coarse[size_t(cy) * size_t(cw) + size_t(cx)];
            bool boundary = false;
            for (int y = std::max(0, cy - 1); y <= std::min(ch - 1, cy + 1) && !boundary; ++y)
                for (int x = std::max(0, cx - 1); x <= std::min(cw - 1, cx + 1); ++x)
                    boundary |= coarse[size_t(y) * size_t(cw) + size_t(x)] != side;
            if (!boundary) continue;
            for (int y = std::max(0, cy - kBand + 1); y <= std::min(ch - 1, cy + kBand - 1); ++y)
                for (int x = std::max(0, cx - kBand + 1); x <= std::min(cw - 1, cx + kBand - 1);
                     ++x)
                    near_cut[size_t(y) * size_t(cw) + size_t(x)] = 1;
        }

    // Fine pixels outside the band keep their pin, or else the coarse cut's side; only the band
    // is a graph, its edges to fixed pixels turned into terminal weights.
    std::vector<uint8_t> take_new(size_t(w) * size_t(h));
    std::vector<int> node(take_new.size(), -1);
    int nodes = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t n = size_t(y) * size_t(w) + size_t(x),
                         c = size_t(y / 2) * size_t(cw) + size_t(x / 2);
            take_new[n] = pins[n] == Pin::New ? 1 : pins[n] == Pin::Old ? 0 : coarse[c];
            if (near_cut[c] && pins[n] == Pin::Free) node[n] = nodes++;
        }
    if (nodes == 0) return take_new;
    auto weight = [&](size_t a, size_t b) { return edge_cost(diff, a, b); };
    cv::detail::GCGraph<float> graph(unsigned(nodes), unsigned(4 * nodes));
    for (int i = 0; i < nodes; ++i)
        graph.addVtx();
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t n = size_t(y) * size_t(w) + size_t(x);
            if (node[n] < 0) continue;
            float to_new = 0, to_old = 0;
            const auto link = [&](size_t m) {
                const float c = weight(n, m);
                if (node[m] >= 0) {
                    if (m > n) graph.addEdges(node[n], node[m], c, c);
                } else {
                    (take_new[m] ? to_new : to_old) += c;
                }
            };
            if (x > 0) link(n - 1);
            if (x + 1 < w) link(n + 1);
            if (y > 0) link(n - size_t(w));
            if (y + 1 < h) link(n + size_t(w));
            if (to_new > 0 || to_old > 0) graph.addTermWeights(node[n], to_new, to_old);
        }
    graph.maxFlow();
    for (size_t n = 0; n < take_new.size(); ++n)
        if (node[n] >= 0) take_new[n] = graph.inSourceSegment(node[n]) ? 1 : 0;
    return take_new;
}

std::vector<uint8_t> cut_levels(const std::vector<float>& diff, int w, int h,
                                const std::vector<Pin>& pins) {
    return std::min(w, h) >= kBandedCutSide ? cut_banded(diff, w, h, pins)
                                            : cut_whole(diff, w, h, pins);
}

}  // namespace

Cut min_cut(const cv::Mat& old_lab, const cv::Mat& new_lab, const std::vector<Pin>& pins,
            CutLevels levels) {
    CV_Assert(pins.size() == old_lab.total());
    const int w = old_lab.cols, h = old_lab.rows;
    const std::vector<float> diff = lab_difference(old_lab, new_lab);
    auto weight = [&](size_t a, size_t b) { return edge_cost(diff, a, b); };

    Cut cut;
    cut.take_new =
        levels == CutLevels::Whole ? cut_whole(diff, w, h, pins) : cut_levels(diff, w, h, pins);
    for (const uint8_t t : cut.take_new)
        cut.taken += t;
    double sum = 0, square = 0;
    size_t edges = 0;
    auto on_edge = [&](size_t a, size_t b) {
        if (cut.take_new[a] == cut.take_new[b]) return;
        const float c = weight(a, b);
        sum += c, ++edges, cut.max_cost = std::max(cut.max_cost, c);
        square += double(c) * c;
    };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t n = size_t(y) * size_t(w) + size_t(x);
            if (x + 1 < w) on_edge(n, n + 1);
            if (y + 1 < h) on_edge(n, n + size_t(w));
        }
    cut.total_cost = sum;
    cut.mean_cost = edges ? sum / double(edges) : 0;
    cut.mean_square_cost = edges ? square / double(edges) : 0;
    return cut;
}

}  // namespace tilejet::synth::detail
