#include "candidate_patch.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "graph_cut.hpp"
#include "tilejet/synth/internal/mix64.hpp"

namespace tilejet::synth::detail {

std::optional<Patch> make_candidate(const CandidateSpace& space, uint64_t seed) {
    Rng rng(seed);
    const double lo = std::log(double(space.min_radius)), hi = std::log(double(space.max_radius));
    const int r = int(std::lround(std::exp(lo + (hi - lo) * rng.unit())));
    // r is the patch's nominal half-width: the forced core spans about 1.4 r, the window 3 r,
    // and the cut settles in between.
    const int core = std::max(1, int(std::lround(0.7 * r)));
    const int R = int(std::ceil(1.5 * r)) + 2;
    const int side = 2 * R + 1;
    const cv::Mat& src = space.source_lab;
    const cv::Mat& canvas = space.canvas_lab;
    if (src.cols < side || src.rows < side) return std::nullopt;
    const auto allowed = [&](int x, int y) {
        return space.grid.in_diamond_interior(x, y) && (!space.exact || space.exact(x, y));
    };

    // p: a position in the cell's own square. Patches centred there stay mostly inside it, and
    // A and B squares form a checkerboard, so few patches conflict across the A/B split. The
    // core must still lie inside the cell's diamond.
    const int cw = int(space.grid.cell_width()), ch = int(space.grid.cell_height());
    int px = 0, py = 0;
    bool placed = false;
    for (int attempt = 0; attempt < 16 && !placed; ++attempt) {
        px = rng.range(0, cw - 1);
        py = rng.range(0, ch - 1);
        placed = allowed(px - core, py - core) && allowed(px + core, py - core) &&
                 allowed(px - core, py + core) && allowed(px + core, py + core);
    }
    if (!placed) return std::nullopt;
    const cv::Point corner = space.canvas_origin + cv::Point(px - R, py - R);
    if (corner.x < 0 || corner.y < 0 || corner.x + side > canvas.cols ||
        corner.y + side > canvas.rows)
        return std::nullopt;
    // q: the source pixel shown at p. Of `offset_draws` random draws, the one that best matches
    // the plane on the ring where the cut will run (every other pixel of it: enough to rank).
    const auto ring_cost = [&](int qx, int qy) {
        double cost = 0;
        for (int dy = -R + 1; dy < R; dy += 2)
            for (int dx = -R + 1; dx < R; dx += 2) {
                if (std::max(std::abs(dx), std::abs(dy)) <= core || !allowed(px + dx, py + dy))
                    continue;
                const cv::Vec3f d = canvas.at<cv::Vec3f>(corner.y + dy + R, corner.x + dx + R) -
                                    src.at<cv::Vec3f>(qy + dy, qx + dx);
                cost += double(d.dot(d));
            }
        return cost;
    };
    int qx = -1, qy = -1;
    double best = 0;
    for (int draw = 0; draw < std::max(1, space.offset_draws); ++draw) {
        cv::Point q(rng.range(R, src.cols - 1 - R), rng.range(R, src.rows - 1 - R));
        if (space.lattice) {
            q = cv::Point(px, py) + space.lattice->near({double(q.x - px), double(q.y - py)}, rng);
            if (q.x < R || q.y < R || q.x > src.cols - 1 - R || q.y > src.rows - 1 - R) continue;
        }
        if (space.offset_draws <= 1) {
            qx = q.x, qy = q.y;
            break;
        }
        const double cost = ring_cost(q.x, q.y);
        if (qx < 0 || cost < best) qx = q.x, qy = q.y, best = cost;
    }
    if (qx < 0) return std::nullopt;

    // The cut between "keep the plane" (the rim, and wherever a patch may not reach) and "take
    // the source" (the core).
    std::vector<Pin> pins(static_cast<size_t>(side) * side, Pin::Free);
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
            const int dx = x - R, dy = y - R;
            const bool rim = x == 0 || y == 0 || x == side - 1 || y == side - 1;
            Pin& pin = pins[size_t(y) * size_t(side) + size_t(x)];
            if (rim || !allowed(px + dx, py + dy))
                pin = Pin::Old;
            else if (std::abs(dx) <= core && std::abs(dy) <= core)
                pin = Pin::New;
        }
    const Cut cut = min_cut(canvas(cv::Rect(corner, cv::Size(side, side))),
                            src(cv::Rect(qx - R, qy - R, side, side)), pins, space.cuts);
    return patch_from_cut(cut, {side, side}, {px - R, py - R}, {qx - R, qy - R},
                          space.mean_seam_cost ? float(cut.mean_cost) : cut.max_cost);
}

std::optional<Patch> patch_from_cut(const Cut& cut, cv::Size window, cv::Point cell_at,
                                    cv::Point source_at, float seam_cost) {
    const auto in = [&](int x, int y) {
        return cut.take_new[size_t(y) * size_t(window.width) + size_t(x)];
    };
    int x0 = window.width, y0 = window.height, x1 = -1, y1 = -1;
    for (int y = 0; y < window.height; ++y)
        for (int x = 0; x < window.width; ++x)
            if (in(x, y)) {
                x0 = std::min(x0, x), x1 = std::max(x1, x);
                y0 = std::min(y0, y), y1 = std::max(y1, y);
            }
    if (x1 < 0) return std::nullopt;

    Patch p;
    p.x = cell_at.x + x0, p.y = cell_at.y + y0;
    p.src_x = source_at.x + x0, p.src_y = source_at.y + y0;
    p.width = x1 - x0 + 1, p.height = y1 - y0 + 1;
    p.bits.assign(size_t(p.height) * size_t(p.row_bytes()), 0);
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x)
            if (in(x, y))
                p.bits[size_t(y - y0) * size_t(p.row_bytes()) + size_t((x - x0) >> 3)] |=
                    uint8_t(1u << ((x - x0) & 7));
    p.seam_cost = seam_cost;
    p.derive_runs();
    return p;
}

}  // namespace tilejet::synth::detail
