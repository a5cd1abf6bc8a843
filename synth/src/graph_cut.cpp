#include "graph_cut.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc/detail/gcgraph.hpp>

namespace tilejet::synth::detail {

Cut min_cut(const cv::Mat& old_lab, const cv::Mat& new_lab, const std::vector<Pin>& pins) {
    CV_Assert(old_lab.type() == CV_32FC3 && new_lab.type() == CV_32FC3 &&
              old_lab.size() == new_lab.size() && pins.size() == old_lab.total());
    const int w = old_lab.cols, h = old_lab.rows;
    std::vector<float> diff(size_t(w) * size_t(h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const cv::Vec3f d = old_lab.at<cv::Vec3f>(y, x) - new_lab.at<cv::Vec3f>(y, x);
            diff[size_t(y) * size_t(w) + size_t(x)] = std::sqrt(d.dot(d));
        }
    auto weight = [&](size_t a, size_t b) { return diff[a] + diff[b] + kEdgeFloor; };

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

    Cut cut;
    cut.take_new.resize(size_t(w) * size_t(h));
    for (size_t n = 0; n < cut.take_new.size(); ++n)
        cut.taken += cut.take_new[n] = graph.inSourceSegment(int(n)) ? 1 : 0;
    double sum = 0;
    size_t edges = 0;
    auto on_edge = [&](size_t a, size_t b) {
        if (cut.take_new[a] == cut.take_new[b]) return;
        const float c = weight(a, b);
        sum += c, ++edges, cut.max_cost = std::max(cut.max_cost, c);
    };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t n = size_t(y) * size_t(w) + size_t(x);
            if (x + 1 < w) on_edge(n, n + 1);
            if (y + 1 < h) on_edge(n, n + size_t(w));
        }
    cut.mean_cost = edges ? sum / double(edges) : 0;
    return cut;
}

}  // namespace tilejet::synth::detail
