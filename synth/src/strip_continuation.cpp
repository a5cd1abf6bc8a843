#include "strip_continuation.hpp"

#include <algorithm>

#include "candidate_patch.hpp"
#include "tilejet/synth/internal/mix64.hpp"

namespace tilejet::synth::detail {

namespace {

// A frame patch reaches at most this share of the cell in from its edge. With two fifths the
// continuation, the same in every image along a strip of one kind, repeated with the strips:
// granite's periodicity 2.12, cobbles' 1.39 at map seed 1 (0.89 and 0.67 without frame
// patches); with a quarter 1.03 and 0.63, the lines along the grid as low (session 35).
constexpr double kDeepestShare = 0.25;
// Beyond the frame a patch's window reaches at least this far, for its cut to have room.
constexpr int kLeastRoom = 12;
// Patches run along at least half the edge between its corners: ranked by their seams alone,
// short ones won and left most of each border to the cell's own cut.
constexpr double kShortestShare = 0.5;
// A patch pixel differing from the image's by more than this (squared CIELab) changes what
// shows; a patch must change an eighth of its pixels.
constexpr float kChanged = 4.0f;

// Distance from the edge (u) and place along it (t), against image pixels.
struct EdgeFrame {
    CellEdge edge;
    int cw, ch;

    bool horizontal() const { return edge == CellEdge::top || edge == CellEdge::bottom; }
    int along() const { return horizontal() ? cw : ch; }
    int across() const { return horizontal() ? ch : cw; }
    // The image rectangle of depths [0, depth) along [t0, t0 + length).
    cv::Rect window(int t0, int length, int depth) const {
        switch (edge) {
            case CellEdge::top:
                return {t0, 0, length, depth};
            case CellEdge::bottom:
                return {t0, ch - depth, length, depth};
            case CellEdge::left:
                return {0, t0, depth, length};
            case CellEdge::right:
                return {cw - depth, t0, depth, length};
        }
        return {};
    }
    int depth_of(cv::Point p) const {
        switch (edge) {
            case CellEdge::top:
                return p.y;
            case CellEdge::bottom:
                return ch - 1 - p.y;
            case CellEdge::left:
                return p.x;
            case CellEdge::right:
                return cw - 1 - p.x;
        }
        return 0;
    }
    int along_of(cv::Point p) const { return horizontal() ? p.x : p.y; }
};

}  // namespace

std::optional<Patch> make_continuation(const ContinuationSpace& space, uint64_t seed) {
    Rng rng(seed);
    const EdgeFrame f{space.edge, space.image_lab.cols, space.image_lab.rows};
    const int w = space.frame;
    // Clear of the corner core the cell shows (a third of the frame, locked); nearer the
    // corner than the frame the cell shows its horizontal and vertical strips cut together,
    // and the cut prices what this strip's continuation does not match there.
    const int margin = std::max(2, w / 3) + 2;
    const int room = f.along() - 2 * margin;
    if (room < 16 || f.across() < 2 * (w + kLeastRoom)) return std::nullopt;
    const int length = rng.range(std::max(16, int(room * kShortestShare)), room);
    const int t0 = margin + rng.range(0, room - length);
    // No deeper than the continuation stays inside the source.
    const cv::Rect whole({0, 0}, space.source_lab.size());
    const auto fits = [&](int depth) {
        const cv::Rect from = f.window(t0, length, depth) + space.offset;
        return (from & whole) == from;
    };
    int deepest = int(f.across() * kDeepestShare);
    while (deepest >= w + kLeastRoom && !fits(deepest))
        --deepest;
    if (deepest < w + kLeastRoom) return std::nullopt;
    const int depth = rng.range(w + kLeastRoom, deepest);
    // The core's depth drawn over all the window leaves room for: where the continuation does
    // not match the cell the cut hugs the core, and should do so at many depths, not one.
    const int core = rng.range(2, std::max(2, depth - w - 6));
    const int inset = std::max(2, length / 8);

    const cv::Rect window = f.window(t0, length, depth);
    const cv::Rect from = window + space.offset;
    std::vector<Pin> pins(size_t(window.area()), Pin::Free);
    for (int y = 0; y < window.height; ++y)
        for (int x = 0; x < window.width; ++x) {
            const cv::Point at = window.tl() + cv::Point(x, y);
            const int u = f.depth_of(at), t = f.along_of(at);
            const bool rim = x == 0 || y == 0 || x == window.width - 1 || y == window.height - 1;
            Pin& pin = pins[size_t(y) * size_t(window.width) + size_t(x)];
            if (u >= w && u < w + core && t >= t0 + inset && t < t0 + length - inset)
                pin = Pin::New;
            else if (rim)
                pin = Pin::Old;
        }
    const cv::Mat image = space.image_lab(window), continuation = space.source_lab(from);
    const Cut cut = min_cut(image, continuation, pins, space.cuts);
    // Where the cell's own blocks continue the strip already (the first image made with a
    // strip may copy its continuation), a patch shows what is there: of no use.
    size_t changed = 0;
    for (int y = 0; y < window.height; ++y)
        for (int x = 0; x < window.width; ++x)
            if (cut.take_new[size_t(y) * size_t(window.width) + size_t(x)]) {
                const cv::Vec3f d = image.at<cv::Vec3f>(y, x) - continuation.at<cv::Vec3f>(y, x);
                changed += d.dot(d) > kChanged;
            }
    if (changed * 8 < cut.taken) return std::nullopt;
    return patch_from_cut(cut, window.size(), window.tl(), from.tl(), float(cut.mean_cost));
}

}  // namespace tilejet::synth::detail
