#include "tilejet/synth/internal/rsgf.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "lattice_alignment.hpp"
#include "tilejet/synth/error.hpp"
#include "tilejet/synth/internal/lab.hpp"
#include "tilejet/synth/internal/mix64.hpp"

namespace tilejet::synth {

namespace {

using detail::LatticeTranslations;
using detail::Rng;

constexpr int kMinBlock = 16;  // px; smaller blocks are mostly border
constexpr int kBlend = 4;      // px of linear blend outside each gap

// Blocks whose sides are lattice vectors, so that neighbouring blocks meet on the same phase
// of the pattern; only when none fits in half the exemplar (a strongly sheared lattice) a
// square about one period, whose copies are still moved by lattice translations.
cv::Size block_size(const Lattice& lattice, const LatticeTranslations& translations,
                    cv::Size exemplar) {
    const int smaller = std::min(exemplar.width, exemplar.height);
    if (lattice.kind == LatticeKind::Stochastic) {
        const int side = std::max(8, smaller / 4);
        return {side, side};
    }
    if (auto rect = translations.cell_size(kMinBlock, {exemplar.width / 2, exemplar.height / 2}))
        return *rect;
    const double period =
        std::max(std::hypot(lattice.v1.x, lattice.v1.y), std::hypot(lattice.v2.x, lattice.v2.y));
    const int side = std::clamp(int(std::lround(period)), std::min(kMinBlock, smaller / 2),
                                std::max(1, smaller / 2));
    return {side, side};
}

// A random exemplar position for a block of `block` at canvas position `at`, a lattice
// translation away from it so the copy lands in phase.
cv::Point random_aligned(const LatticeTranslations& translations, cv::Point at, cv::Size block,
                         cv::Size exemplar, Rng& rng) {
    const int max_x = exemplar.width - block.width, max_y = exemplar.height - block.height;
    cv::Point q;
    for (int attempt = 0; attempt < 64; ++attempt) {
        const cv::Point target(rng.range(0, max_x), rng.range(0, max_y));
        q = at + translations.nearest(cv::Point2d(target - at));
        if (q.x >= 0 && q.y >= 0 && q.x <= max_x && q.y <= max_y) return q;
    }
    return {std::clamp(q.x, 0, max_x), std::clamp(q.y, 0, max_y)};
}

struct Canvas {
    cv::Mat rgb;
    cv::Size block;
    int blend;
    cv::Rect cell(int i, int j) const {
        return {i * block.width, j * block.height, block.width, block.height};
    }
};

// The gap `cell` grown by the blend width, and which of its pixels are border to match: the
// four strips beside the gap that lie on the canvas (not the corners, which belong to other
// gaps, filled or not).
cv::Mat border_mask(const Canvas& c, cv::Rect cell) {
    const int m = c.blend;
    cv::Mat mask(cell.height + 2 * m, cell.width + 2 * m, CV_32FC3, cv::Scalar::all(0));
    const cv::Rect strips[] = {{0, m, m, cell.height},
                               {m + cell.width, m, m, cell.height},
                               {m, 0, cell.width, m},
                               {m, m + cell.height, cell.width, m}};
    const cv::Rect canvas(0, 0, c.rgb.cols, c.rgb.rows);
    const cv::Point origin = cell.tl() - cv::Point(m, m);
    for (const cv::Rect& s : strips) {
        const cv::Rect on_canvas = (s + origin) & canvas;
        if (on_canvas.area() == s.area()) mask(s).setTo(cv::Scalar::all(1));
    }
    return mask;
}

// The exemplar position (of the grown gap) within +-3 px of a lattice translation whose border
// strips differ least from the canvas, in CIELab.
cv::Point best_border_match(const Canvas& c, cv::Rect cell, const cv::Mat& exemplar_lab,
                            const LatticeTranslations& translations) {
    const int m = c.blend;
    const cv::Rect grown(cell.x - m, cell.y - m, cell.width + 2 * m, cell.height + 2 * m);
    cv::Mat patch;
    // Pixels off the canvas are masked out; replicate only to give the template a size.
    cv::copyMakeBorder(c.rgb(grown & cv::Rect(0, 0, c.rgb.cols, c.rgb.rows)), patch,
                       std::max(0, -grown.y), std::max(0, grown.br().y - c.rgb.rows),
                       std::max(0, -grown.x), std::max(0, grown.br().x - c.rgb.cols),
                       cv::BORDER_REPLICATE);
    cv::Mat cost;
    cv::matchTemplate(exemplar_lab, detail::to_lab(patch), cost, cv::TM_SQDIFF,
                      border_mask(c, cell));
    cv::Point best(-1, -1);
    float best_cost = 0;
    for (int y = 0; y < cost.rows; ++y)
        for (int x = 0; x < cost.cols; ++x) {
            const float v = cost.at<float>(y, x);
            if ((best.x < 0 || v < best_cost) && translations.allows(cv::Point(x, y) - grown.tl()))
                best = {x, y}, best_cost = v;
        }
    return best;
}

// Copies the grown gap from the exemplar: the gap itself as is, the strips beside it blended
// linearly from the gap's content at its edge to the block's kBlend px away.
void fill_gap(Canvas& c, cv::Rect cell, const cv::Mat& exemplar, cv::Point from) {
    const int m = c.blend;
    for (int y = -m; y < cell.height + m; ++y)
        for (int x = -m; x < cell.width + m; ++x) {
            const int cx = cell.x + x, cy = cell.y + y;
            if (cx < 0 || cy < 0 || cx >= c.rgb.cols || cy >= c.rgb.rows) continue;
            const int out_x = x < 0 ? -x : std::max(0, x - cell.width + 1);
            const int out_y = y < 0 ? -y : std::max(0, y - cell.height + 1);
            if (out_x && out_y) continue;  // a corner: another gap's
            const double alpha = 1 - double(std::max(out_x, out_y)) / (m + 1);
            const cv::Vec3b src = exemplar.at<cv::Vec3b>(from.y + y + m, from.x + x + m);
            cv::Vec3b& dst = c.rgb.at<cv::Vec3b>(cy, cx);
            for (int k = 0; k < 3; ++k)
                dst[k] = cv::saturate_cast<uint8_t>(alpha * src[k] + (1 - alpha) * dst[k]);
        }
}

}  // namespace

cv::Mat synthesize_rsgf(const cv::Mat& exemplar, const Lattice& lattice, cv::Size size,
                        uint64_t seed) {
    if (exemplar.type() != CV_8UC3) throw SynthError("rsgf needs an 8-bit R,G,B exemplar");
    const LatticeTranslations translations(lattice);
    const cv::Size block = block_size(lattice, translations, exemplar.size());
    const int blend = std::min(kBlend, std::min(block.width, block.height) / 4);
    if (block.width + 2 * blend > exemplar.cols || block.height + 2 * blend > exemplar.rows)
        throw SynthError("exemplar " + std::to_string(exemplar.cols) + "x" +
                         std::to_string(exemplar.rows) + " px is too small for rsgf blocks of " +
                         std::to_string(block.width) + "x" + std::to_string(block.height) + " px");

    const int nx = (size.width + block.width - 1) / block.width,
              ny = (size.height + block.height - 1) / block.height;
    Canvas c{cv::Mat(ny * block.height, nx * block.width, CV_8UC3, cv::Scalar::all(0)), block,
             blend};
    Rng rng(detail::hash_combine(seed, 0x6a95ull));
    for (int j = 0; j < ny; ++j)
        for (int i = (j % 2); i < nx; i += 2) {
            const cv::Rect cell = c.cell(i, j);
            const cv::Point from =
                random_aligned(translations, cell.tl(), block, exemplar.size(), rng);
            exemplar(cv::Rect(from, block)).copyTo(c.rgb(cell));
        }

    const cv::Mat exemplar_lab = detail::to_lab(exemplar);
    const cv::Size grown(block.width + 2 * blend, block.height + 2 * blend);
    for (int j = 0; j < ny; ++j)
        for (int i = 1 - (j % 2); i < nx; i += 2) {
            const cv::Rect cell = c.cell(i, j);
            cv::Point from = best_border_match(c, cell, exemplar_lab, translations);
            if (from.x < 0)  // no aligned position fits: any in-phase one, unmatched
                from = random_aligned(translations, cell.tl() - cv::Point(blend, blend), grown,
                                      exemplar.size(), rng);
            fill_gap(c, cell, exemplar, from);
        }
    return c.rgb(cv::Rect({0, 0}, size)).clone();
}

}  // namespace tilejet::synth
