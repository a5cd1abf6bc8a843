#include "cell_set.hpp"

#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "graph_cut.hpp"
#include "lab.hpp"
#include "measure/parallel_for.hpp"
#include "mix64.hpp"
#include "offset_matching.hpp"
#include "tilejet/synth/error.hpp"

namespace tilejet::synth::detail {

namespace {

enum Stream : uint64_t { kCornerStream = 11, kStripStream, kImageStream };

// Quilting's own tolerance (design.md section 2.2): a block is drawn among the source windows
// within 10% of the best match.
constexpr double kMatchTolerance = 0.1;
// Blocks are drawn among at least this many distinct good matches (offset_matching.hpp):
// with one, images that share a frame's side copied the same blocks along it, and the wall's
// autocorrelation peaked at whole cells (demo design: periodicity 1.9 against 1.0 with two);
// with three or more the blocks matched so much worse that the cells showed as squares.
constexpr int kMinChoices = 2;
// Block searches look at a random window of the source this many positions across.
constexpr int kSearchWindow = 384;

// A canvas being quilted: what is there (R,G,B and CIELab) and which pixels are known.
struct Canvas {
    cv::Mat rgb, lab;
    cv::Mat known;   // CV_8U, 255 where the canvas already shows something
    cv::Mat locked;  // CV_8U, 255 where it must keep what it shows: what neighbours share

    explicit Canvas(cv::Size size)
        : rgb(size, CV_8UC3, cv::Scalar::all(0)),
          lab(size, CV_32FC3, cv::Scalar::all(0)),
          known(size, CV_8U, cv::Scalar::all(0)),
          locked(size, CV_8U, cv::Scalar::all(0)) {}

    void paste(const cv::Mat& piece_rgb, const cv::Mat& piece_lab, cv::Point at) {
        const cv::Rect r(at, piece_rgb.size());
        piece_rgb.copyTo(rgb(r));
        piece_lab.copyTo(lab(r));
        known(r).setTo(255);
    }
};

// Starts of `count` blocks that cover [begin, end) with at least `overlap` between neighbours.
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

}  // namespace

CellSet::CellSet(const cv::Mat& source_rgb, const cv::Mat& source_lab, const CellSetParams& params)
    : source_rgb_(source_rgb),
      source_lab_(source_lab),
      params_(params),
      k_(params.corner_colours),
      cw_(params.cell.width),
      ch_(params.cell.height) {
    if (k_ < 2) throw SynthError("a cell set needs at least 2 corner colours");
    const int side = std::min(cw_, ch_);
    // Blocks of a quarter cell (design.md section 2.2), overlaps of a quarter block, a little
    // wider than the design's sixth so that seams can find where blocks agree. Half-cell blocks
    // with half-block overlaps scored better on texture energy (1.12 times quilting's on the
    // demo design) but, from a 256 px exemplar, put the same few best-matching blocks in cell
    // after cell: a wall of repeated veins (periodicity 2.6).
    // The frame is thin, since what neighbours share is the same in every image with those
    // corners and repeats as often; only its outer pixel is locked, and the cells' own blocks
    // cut into the rest.
    block_ = std::max(8, side / 4);
    overlap_ = std::max(2, block_ / 4);
    w_ = std::max(3, side / 16);
    if (source_rgb.cols < cw_ + 2 * w_ + 2 || source_rgb.rows < ch_ + 2 * w_ + 2)
        throw SynthError("the source is too small for a cell set of this cell size");

    choose_corner_blocks();
    const size_t kinds = size_t(k_) * size_t(k_);
    horizontal_.resize(kinds), vertical_.resize(kinds);
    parallel_for(2 * kinds, params.threads, [&](size_t i) {
        const uint32_t a = uint32_t(i % kinds % size_t(k_)), b = uint32_t(i % kinds / size_t(k_));
        if (i < kinds)
            horizontal_[i] = make_strip(true, a, b);
        else
            vertical_[i - kinds] = make_strip(false, a, b);
    });
    images_.resize(kinds * kinds);
    parallel_for(images_.size(), params.threads, [&](size_t m) { images_[m] = make_image(m); });
}

namespace {

// Where `canvas`'s unknown pixels inside `rect` should copy from, and the seam: the source
// window that best matches the known pixels there (within the tolerance, lattice translations
// only on a lattice), then a minimum-cost cut through the known pixels near the unknown ones.
// The cut may replace known pixels within `overlap` of the unknown ones, never the rest.
// `origin` is the plane position of the canvas's top-left pixel relative to a lattice point.
void quilt_block(Canvas& canvas, const cv::Rect& rect, int overlap, const cv::Mat& source_rgb,
                 const cv::Mat& source_lab, const LatticeTranslations* lattice, cv::Point origin,
                 Rng& rng) {
    const cv::Mat known = canvas.known(rect);
    cv::Mat unknown = known == 0, near;
    if (cv::countNonZero(unknown) == 0) return;
    cv::dilate(unknown, near,
               cv::getStructuringElement(cv::MORPH_RECT, {2 * overlap + 1, 2 * overlap + 1}));
    // Like quilting, the match counts only the overlap, where the seam will run (locked pixels
    // next to it too: the seam runs along them): known pixels deeper in are kept whatever the
    // new block holds there.
    cv::Mat mask;
    cv::Mat overlap_band = known & near;
    overlap_band.convertTo(mask, CV_32F, 1.0 / 255);
    const OffsetSearch search{
        source_lab,
        [&](cv::Point corner) { return !lattice || lattice->allows(corner - rect.tl() - origin); },
        kMatchTolerance,
        kMinChoices,
        std::max(4, overlap / 2),
        kSearchWindow};
    std::optional<cv::Point> corner;
    if (cv::countNonZero(mask) > 0) corner = match_offset(search, canvas.lab(rect), mask, rng);
    if (!corner) {  // nothing to match yet (or no lattice offset fits): anywhere
        corner = cv::Point(rng.range(0, source_lab.cols - rect.width),
                           rng.range(0, source_lab.rows - rect.height));
        if (lattice)
            *corner =
                rect.tl() + origin + lattice->nearest(cv::Point2d(*corner - rect.tl() - origin));
        corner->x = std::clamp(corner->x, 0, source_lab.cols - rect.width);
        corner->y = std::clamp(corner->y, 0, source_lab.rows - rect.height);
    }
    const cv::Rect from(*corner, rect.size());
    std::vector<Pin> pins(size_t(rect.area()));
    for (int y = 0; y < rect.height; ++y)
        for (int x = 0; x < rect.width; ++x) {
            Pin& pin = pins[size_t(y) * size_t(rect.width) + size_t(x)];
            const bool rim = x == 0 || y == 0 || x == rect.width - 1 || y == rect.height - 1;
            if (unknown.at<uint8_t>(y, x))
                pin = Pin::New;
            else if (rim || canvas.locked.at<uint8_t>(rect.y + y, rect.x + x))
                pin = Pin::Old;
            else
                pin = near.at<uint8_t>(y, x) ? Pin::Free : Pin::Old;
        }
    const Cut cut = min_cut(canvas.lab(rect), source_lab(from), pins);
    for (int y = 0; y < rect.height; ++y)
        for (int x = 0; x < rect.width; ++x)
            if (cut.take_new[size_t(y) * size_t(rect.width) + size_t(x)]) {
                canvas.rgb.at<cv::Vec3b>(rect.y + y, rect.x + x) =
                    source_rgb.at<cv::Vec3b>(from.y + y, from.x + x);
                canvas.lab.at<cv::Vec3f>(rect.y + y, rect.x + x) =
                    source_lab.at<cv::Vec3f>(from.y + y, from.x + x);
                canvas.known.at<uint8_t>(rect.y + y, rect.x + x) = 255;
            }
}

// Quilts the unknown pixels of `area` in raster order with blocks of about `block` px.
void quilt_area(Canvas& canvas, const cv::Rect& area, int block, int overlap,
                const cv::Mat& source_rgb, const cv::Mat& source_lab,
                const LatticeTranslations* lattice, cv::Point origin, Rng& rng) {
    // A thin strip gets blocks as tall as itself, overlapping by at most half a block.
    const int bh = std::min(block, area.height), bw = std::min(block, area.width);
    const auto rows = block_spans(area.y, area.br().y, bh, std::min(overlap, bh / 2));
    const auto cols = block_spans(area.x, area.br().x, bw, std::min(overlap, bw / 2));
    for (const auto& [y0, y1] : rows)
        for (const auto& [x0, x1] : cols)
            quilt_block(canvas, cv::Rect(x0, y0, x1 - x0, y1 - y0), overlap, source_rgb, source_lab,
                        lattice, origin, rng);
}

}  // namespace

void CellSet::choose_corner_blocks() {
    // Spread over the source: each the farthest of a few random draws from those taken.
    Rng rng(hash_combine(params_.seed, kCornerStream));
    const int x_hi = source_rgb_.cols - 2 * w_, y_hi = source_rgb_.rows - 2 * w_;
    for (int c = 0; c < k_; ++c) {
        cv::Point best(-1, -1);
        double best_distance = -1;
        for (int draw = 0; draw < 32; ++draw) {
            cv::Point s(rng.range(0, x_hi), rng.range(0, y_hi));
            // On a lattice the vertex, w px inside the block, copies a lattice translation of
            // itself, as every cell corner is a lattice point.
            if (params_.lattice)
                s = params_.lattice->nearest({double(s.x + w_), double(s.y + w_)}) -
                    cv::Point(w_, w_);
            if (s.x < 0 || s.y < 0 || s.x > x_hi || s.y > y_hi) continue;
            double distance = 1e300;
            for (const cv::Point& other : corner_source_)
                distance = std::min(distance, cv::norm(s - other));
            if (distance > best_distance) best = s, best_distance = distance;
        }
        if (best.x < 0) throw SynthError("no lattice-aligned corner block fits in the source");
        corner_source_.push_back(best);
    }
}

cv::Mat CellSet::make_strip(bool horizontal, uint32_t a, uint32_t b) const {
    // Strip coordinates: the first vertex's block at the origin, the second's a cell further.
    const cv::Size size =
        horizontal ? cv::Size(cw_ + 2 * w_, 2 * w_) : cv::Size(2 * w_, ch_ + 2 * w_);
    Canvas canvas(size);
    const cv::Point second = horizontal ? cv::Point(cw_, 0) : cv::Point(0, ch_);
    const cv::Rect block_a(corner_source_[a], cv::Size(2 * w_, 2 * w_));
    const cv::Rect block_b(corner_source_[b], cv::Size(2 * w_, 2 * w_));
    canvas.paste(source_rgb_(block_a), source_lab_(block_a), {0, 0});
    canvas.paste(source_rgb_(block_b), source_lab_(block_b), second);
    Rng rng(hash_combine(hash_combine(params_.seed, kStripStream),
                         uint64_t(horizontal) * 65536 + uint64_t(a) * uint64_t(k_) + b));
    // The corner blocks stay whole: the four quarters around a vertex come from four strips,
    // and meet seamlessly only through the block they all hold.
    canvas.locked.setTo(255, canvas.known);
    // The strip's top-left pixel lies (w, w) before its first vertex, a lattice point.
    quilt_area(canvas, cv::Rect({0, 0}, size), block_, overlap_, source_rgb_, source_lab_,
               params_.lattice, {-w_, -w_}, rng);
    return canvas.rgb;
}

cv::Mat CellSet::make_image(size_t index) const {
    const size_t k = size_t(k_);
    const uint32_t tl = uint32_t(index % k), tr = uint32_t(index / k % k),
                   bl = uint32_t(index / k / k % k), br = uint32_t(index / k / k / k);
    Canvas canvas({cw_, ch_});
    const auto paste_rgb = [&](const cv::Mat& rgb, const cv::Rect& from, cv::Point at) {
        const cv::Mat piece = rgb(from);
        canvas.paste(piece, to_lab(piece), at);
    };
    // The frame: the cell's halves of its four strips (which hold the corner blocks' quarters).
    paste_rgb(horizontal_[tl + k * tr], cv::Rect(w_, w_, cw_, w_), {0, 0});
    paste_rgb(horizontal_[bl + k * br], cv::Rect(w_, 0, cw_, w_), {0, ch_ - w_});
    paste_rgb(vertical_[tl + k * bl], cv::Rect(w_, w_, w_, ch_), {0, 0});
    paste_rgb(vertical_[tr + k * br], cv::Rect(0, w_, w_, ch_), {cw_ - w_, 0});
    // The cell's outer pixels stay the strips': they meet the neighbours' across the edge.
    canvas.locked.setTo(255);
    canvas.locked(cv::Rect(1, 1, cw_ - 2, ch_ - 2)).setTo(0);
    Rng rng(hash_combine(hash_combine(params_.seed, kImageStream), index));
    quilt_area(canvas, cv::Rect(0, 0, cw_, ch_), block_, overlap_, source_rgb_, source_lab_,
               params_.lattice, {0, 0}, rng);
    return canvas.rgb;
}

cv::Mat CellSet::neighbourhood(size_t index) const {
    const size_t k = size_t(k_);
    const uint32_t corner[2][2] = {{uint32_t(index % k), uint32_t(index / k % k)},
                                   {uint32_t(index / k / k % k), uint32_t(index / k / k / k)}};
    // Vertices beyond the cell's own four take the colour of the nearest of them.
    const auto colour = [&](int vi, int vj) {
        return corner[std::clamp(vj, 0, 1)][std::clamp(vi, 0, 1)];
    };
    cv::Mat out(3 * ch_, 3 * cw_, CV_8UC3);
    for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
            const size_t m = colour(i, j) + k * (colour(i + 1, j) +
                                                 k * (colour(i, j + 1) + k * colour(i + 1, j + 1)));
            images_[m].copyTo(out(cv::Rect((i + 1) * cw_, (j + 1) * ch_, cw_, ch_)));
        }
    return out;
}

}  // namespace tilejet::synth::detail
