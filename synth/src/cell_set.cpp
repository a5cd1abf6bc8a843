#include "cell_set.hpp"

#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "cell_layout.hpp"
#include "graph_cut.hpp"
#include "layer_steps.hpp"
#include "offset_matching.hpp"
#include "tilejet/synth/error.hpp"
#include "tilejet/synth/internal/corner_colours.hpp"
#include "tilejet/synth/internal/lab.hpp"
#include "tilejet/synth/internal/mix64.hpp"
#include "tilejet/synth/internal/parallel_for.hpp"

namespace tilejet::synth::detail {

namespace {

enum Stream : uint64_t { kCornerStream = 11, kStripStream, kImageStream, kLayoutStream };

// Block searches look at a random window of the source this many positions across, or twice the
// block when that is more: in a window narrower than that, a 480 px block of a 1843 px source
// (the demo design at 360 dpi) found no continuation of a vein it had to continue, and its cut
// ran along the overlap's edge: white shards with straight sides.
constexpr int kSearchWindow = 384;
// Block searches of slab scans (slab_scan(): sources that 81 images copy less than once) also
// look at the whole source coarse to fine (OffsetSearch::coarse), from a copy at most this
// large: an 8192 px slab's lines along the cell grid 1.34 against 1.90, its white shards gone,
// texture energy 1.16 times quilting's against 1.14. Not on smaller sources: a 4096 px slab's
// texture energy rose from 1.18 to 1.34 (blocks drew on the source's calm places), the demo
// design's at 360 dpi (large cells, whose wide windows hold most of their source) from 1.40
// to 1.65. Not on a lattice, whose few allowed offsets a coarse place may miss.
constexpr int kCoarseSide = 1024;
// Each block takes the best seam of this many best-matching windows.
constexpr size_t kCutCandidates = 6;
// What a unit of tone step (seam_tone.hpp: CIELab, blurred over a fortieth of the cell, the
// tone a person sees from a few steps back, as `tilejet eval`'s lines along the cell grid
// measure it) costs against a unit of seam cost when a block picks its window. Measured on the
// corpus at map seeds 1 and 2 (session 41; lines along the cell grid without -> with): slate
// 1.34 -> 1.25 at both, limestone 1.22 -> 1.19 and 1.21 -> 1.20, marble 1.18 -> 1.15 at both,
// wood 1.76 -> 1.69 and 1.67 -> 1.68, granite 1.17 -> 1.20 and 1.19 -> 1.20; texture energy
// within 0.1 of before, all passing. 1 did about as well, 10 no better: the six windows are
// what there is to choose from (twelve: limestone 1.13, granite 1.12, a build 60 % longer).
// Not on a lattice: the brick wall's lines rose (1.38 -> 1.45, 1.41 -> 1.43), its grout
// lines being the design's steps of tone. Nor for cells over kLargeCell: the demo design at
// 360 dpi, whose blocks weigh conspicuous features and judge cuts by their squared cost, went
// from 0.65 / 0.95 / 1.05 to 1.08 / 0.94 / 1.20 (periodicity / texture energy / lines), the
// 4096 px slab from 0.53 / 1.12 / 1.32 to 0.57 / 1.17 / 1.30. Nor where cuts are blended
// (exemplars enlarged twice or more): a window with a smaller tone step but a costlier cut
// left sharper steps in the soft stone (tests/synth/test_cell_sets.cpp, the demo design's
// middle enlarged 4 times: steps sharper than its own 0.1 % 0.13 -> 0.18 of the hard cuts').
// Nor from sources under kSmallSource (pattern files), whose blocks have few windows to choose
// from: a 128 px granite crop's set correlated 1.29 times its quilt's peak, over the gate
// (tests/quality/test_periodicity.cpp).
constexpr double kToneStepCost = 3;
// Images are made this many at a time (see the constructor): images of one batch do not see
// each other's blocks, and with 16 images in batches of 8, the demo design's images took the
// same least-used source over and over (periodicity 1.26, 1.07 in batches of 2).
constexpr size_t kImageBatch = 2;
// Copying a source pixel once more costs this share of the source's variance per overlap pixel
// in the block search: 0.1 still left flat brown bands of strip round marble's cells, 0.5 keeps
// its veins and its colours in every part of the set (1.5 made the demo design's periodicity
// 1.39 against 1.07, and its texture energy no better).
constexpr double kUsageCost = 0.5;
// A block copying its source to the same place of the cell as an earlier image's block costs
// this share of the source's variance per overlap pixel (times how much of it would coincide):
// twice the usage cost, as the copy repeats where the eye compares, at the same place of two
// cells. A hard ban left three blocks in five no window at all on the corpus's 384 px designs,
// and they went in at random: seams, and the design's texture energy 1.32-1.47 times quilting's
// (limestone, gravel, setts) against 1.13-1.29 with the cost. The very window (kRepeatReach) is
// banned all the same (CellSet's constructor), a few dozen of thousands.
constexpr double kSamePlaceCost = 1.0;
// Fifths of the frame a straight frame keeps of its strips (kept_depths()).
constexpr int kKeptFrameFifths = 2;
// Two images' blocks copy the same window to the same place when their sources lie within this
// many px; an image may not (CellSet's constructor).
constexpr int kRepeatReach = 4;
// A source's few conspicuous features (the demo design's one white vein) catch the eye wherever
// they recur. A region is conspicuous where its pixels are, on average over a sixteenth of the
// cell, further from the source's mean colour than this many standard deviations (squared):
// a feature, not the grain. Taken pixel by pixel, 12-15 % of every corpus design was
// conspicuous (granite's dark and white grains, brick's mortar); its strips and corners all
// came from its few calm places, and the cell grid showed (granite's periodicity 1.95 against
// 1.02; gravel's texture energy 1.31 against 1.18). Lattices (grout lines) are left out.
constexpr double kConspicuousZ2 = 2.0;
// Copying a conspicuous pixel costs this many times its squared excess (in units of the source's
// variance) for every copy other images and strips made before, and a strip pays for its first
// copy too: a strip's features recur at a quarter of all cell edges (K = 2), a cell image's at
// one cell in 36. Until session 36 images paid for the first copy as well, and searched up to
// four windows for a match with nothing conspicuous, which kept the demo design's white veins out
// of the set (the demo's white vein, copied into one image, had shown as the same white comma
// three times in 5120 px): its wall was calmer and darker than the stone (light tail 0.2 % of the
// wall against quilting's 1.4 %, texture energy 1.40 times quilting's, completeness the most of
// it). With an image's first copy free and cuts chosen by their mean squared cost
// (quilt_block()), and 3 px blends (build.cpp), 1.07 and 1.18 at map seeds 1 and 2, the veins
// back in a few images each (README, session 37).
constexpr double kConspicuousCost = 1.0;
// Cells larger than this (those of exemplars of 1024 px and more) get the cost of conspicuous
// pixels and the wider block search, when the set must copy its source more than once. Where it
// need not (an 8192 px slab: its set covers a tenth of it) features do not recur, and the wide
// search made blocks converge on the source's calm places (the wall's mean colour 6.4 ΔE from
// the exemplar's against 3.2, texture energy 1.05 against 0.82). On the corpus's 256-320 px cells
// the cost made things worse (limestone's periodicity 0.36 to 1.28, the 256 px demo design's 0.96
// to 1.5: strips from its few calm places, alike at every fourth edge), and those designs showed no
// repeated feature.
constexpr int kLargeCell = CellSet::kLargeCell;
// Large cells' blocks overlap by this part of a block (a quarter elsewhere): a block of light
// cloud among darker ones had a quarter of its 480 px to cut round the cloud in, and where the
// cloud reached into that band the cut ran straight along the band's edge, a square of cloud
// with straight sides, a white vein cut off square (the demo design at 360 dpi, map seeds 1-3:
// texture energy 1.07 / 1.18 / 0.93 times quilting's, lines along the cell grid 1.12 / 1.12 /
// 1.14). Overlapping by half a block, the cut finds the cloud's own edge more often: 0.95 /
// 1.01 / 1.08, lines 1.05 / 1.06 / 1.24 (at seed 3 clouds meet the frame in straight upright
// edges), the white shards gone; the 2048 px slab 1.02 -> 0.99 (lines 1.13 -> 1.10). A third:
// 0.89 at seed 1, but veins cut off square as before. A build takes a quarter longer.
constexpr int kLargeCellOverlapParts = 2;
// A corner's core shows whole at every vertex of its colour, half of all vertices with K = 2:
// on marble at map seed 4 a white fleck in one core stood at every other vertex, a grid of
// dots plain at a glance. Its pixels, one by one, should stay within this many standard
// deviations (squared) of the source's mean colour: the blurred measure of large cells averages
// a fleck of a few pixels away.
constexpr double kCoreZ2 = 4.0;

// A canvas being quilted: what is there (R,G,B and CIELab) and which pixels are known.
struct Canvas {
    cv::Mat rgb, lab;
    cv::Mat known;   // CV_8U, 255 where the canvas already shows something
    cv::Mat locked;  // CV_8U, 255 where it must keep what it shows: what neighbours share
    // Blocks quilted in, and blocks of other canvases this one must not copy again at the same
    // place: the same source at the same place in two images repeats on the cell grid.
    std::vector<Placement> placed;
    const std::vector<Placement>* avoid = nullptr;
    // Blocks whose windows this canvas must not copy to the same place at all (repeats()):
    // those of a batch-mate it repeated once already (CellSet's constructor).
    const std::vector<Placement>* banned = nullptr;
    // How often each source pixel has been copied into the set so far (CV_32F), or none.
    const cv::Mat* usage = nullptr;
    double usage_weight = 0;  // match cost of copying a pixel once more, per overlap pixel
    // Match cost, per overlap pixel, of a window showing an `avoid` block's copy again at the
    // same place.
    double same_place_weight = 0;
    // How conspicuous each source pixel is, as a match cost (CV_32F), or none: each use of it
    // costs that much, the first one too.
    const cv::Mat* conspicuous = nullptr;
    // The uses conspicuous pixels are charged for, when not `usage`: those of every variant.
    const cv::Mat* conspicuous_uses = nullptr;
    // Whether a canvas's first copy of a conspicuous pixel is charged (strips: see
    // kConspicuousCost).
    bool conspicuous_first_charged = true;
    // Large cells: the block search looks at twice the block (kSearchWindow).
    bool wide_search = false;
    // The source made smaller, for searches coarse to fine (OffsetSearch::coarse), or none.
    const cv::Mat* coarse = nullptr;
    int coarse_factor = 1;
    int feather = 0;  // CellSetParams::seam_feather
    // The source's tone, against which each block's cut is judged for its tone step too, or none.
    const SourceTone* tone = nullptr;
    CutLevels cuts = CutLevels::Whole;  // CellSetParams::cuts
    // What each pixel shows most of (CV_32S, an index into `layers`; -1 nothing yet): where the
    // tone steps between copies lie (layer_steps.hpp).
    cv::Mat layer_of;
    std::vector<CanvasLayer> layers;

    explicit Canvas(cv::Size size)
        : rgb(size, CV_8UC3, cv::Scalar::all(0)),
          lab(size, CV_32FC3, cv::Scalar::all(0)),
          known(size, CV_8U, cv::Scalar::all(0)),
          locked(size, CV_8U, cv::Scalar::all(0)),
          layer_of(size, CV_32S, cv::Scalar(-1)) {}

    void paste(const cv::Mat& piece_rgb, const cv::Mat& piece_lab, cv::Point at) {
        const cv::Rect r(at, piece_rgb.size());
        piece_rgb.copyTo(rgb(r));
        piece_lab.copyTo(lab(r));
        known(r).setTo(255);
    }
};

// Adds one use for each source pixel `blocks` copied (their whole windows: what the cut kept
// of each is not worth tracking) to `usage`, which counts the source pixels of `area` (all of
// the source when `area` is its whole).
void count_uses(cv::Mat& usage, const std::vector<Placement>& blocks, const cv::Rect& area) {
    for (const Placement& p : blocks)
        if (const cv::Rect r = cv::Rect(p.source, p.at.size()) & area; !r.empty())
            usage(r - area.tl()) += 1;
}

// Whether blocks at `a` and `b` share a good part of their places in the cell: a quarter of the
// smaller. Since images' joints lie at places of their own (cell_layout.hpp) their blocks seldom
// share a rectangle exactly, and compared only then, images copied one window to one place.
bool share_places(const cv::Rect& a, const cv::Rect& b) {
    return 4 * int64_t((a & b).area()) >= int64_t(std::min(a.area(), b.area()));
}

// The window a block at `rect` would copy to show what block `b` copied at the very same places
// of the cell.
cv::Point same_place_window(const cv::Rect& rect, const Placement& b) {
    return b.source - (b.at.tl() - rect.tl());
}

// Whether block `a` copies (nearly) what `b` copied to the same places of its cell.
bool repeats(const Placement& a, const Placement& b) {
    const cv::Point d = a.source - same_place_window(a.at, b);
    return share_places(a.at, b.at) && std::max(std::abs(d.x), std::abs(d.y)) < kRepeatReach;
}

void count_uses(cv::Mat& usage, const std::vector<Placement>& blocks) {
    count_uses(usage, blocks, cv::Rect({0, 0}, usage.size()));
}

// Half the width of a strip: the frame's share of each cell along an edge, a tenth (why: the
// constructor) or `parts`.
constexpr int kFrameParts = 10;
int frame_width(cv::Size cell, int parts = kFrameParts) {
    return std::max(3, std::min(cell.width, cell.height) / parts);
}

// How far into the cell, of the w px of strip along each edge, a cell keeps what its strip shows
// before its own blocks cut in: the cut runs within that much of the edge, the rest is the
// blocks'. With all w, cuts ran 15-24 px inside each 25 px frame (limestone, 256 px cells) and
// the strips, the same at one edge in K^2, stayed a third of the plane: a 1 Mpx stretch of wall
// showed little more of the source than the few windows strips were cut from (limestone at map
// seed 2: completeness 0.66 against quilting's 0.59, texture energy 1.42 times quilting's).
// Over the corpus at map seeds 1 and 2 (session 30), texture energy against quilting's: all w
// 0.92 on average, worst 1.42; three fifths 0.85, worst 1.17; two fifths 0.78, worst 1.05.
// No line shows along the cell borders: row-to-row jumps within 2 px of them 0.81-1.27 times
// the mean, as before (0.86-1.23; marble and wood the widest).
// The cut needs room all the same: to go round the quarter of a corner core (c px, locked) that
// the cell's corner shows, and where cuts are blended, to blend over `feather` px each side
// (an exemplar enlarged 4 times: steps sharper than the stone's 0.41 % with a kept frame of 3
// px, 0.13 % with all of it).
// Since session 32 (CellSetParams::wandering) that depth wanders, image by image, between the
// least the cut needs and the whole frame (cell_layout.hpp): kept at the same depth in every
// image, every cell's cut ran in the same thin band and outlined it (the corpus's marble at map
// seed 1, lines along the cell grid 1.31 against 1.15 wandering; slate 1.47 against 1.30).
KeptDepths kept_depths(int w, int c, int feather, bool wandering) {
    const int room = std::min(w, c + 2), blend = std::min(w, 2 * feather + 2);
    if (!wandering) {
        const int kept = std::max({2, w * kKeptFrameFifths / 5, room, blend});
        return {kept, kept, kept, 0};
    }
    const int least = std::max(2, blend);
    return {least, std::max(least, w), std::max(least, room), c + 2};
}

// Whether a set of K `k` for `cell` from `source` has large cells: over kLargeCell, from a
// source its K^4 images copy more than once (the demo design at 360 dpi covers its 1843 px
// source twice, an 8192 px slab a tenth of its source).
bool large_cells(int k, cv::Size cell, cv::Size source) {
    const double reuse =
        double(k) * k * k * k * cell.width * cell.height / (double(source.width) * source.height);
    return std::min(cell.width, cell.height) > kLargeCell && reuse >= 1;
}

// The smallest source a set of `cell` with a frame of `w` can be made from
// (CellSet::smallest_source says why).
cv::Size least_source(cv::Size cell, int w) {
    return {std::max(8, cell.width * 3 / 4) + 2 * w + 2,
            std::max(8, cell.height * 3 / 4) + 2 * w + 2};
}

// Cells up to kLargeCell from a source of kSmallSource or more: a design of a few hundred px
// at its own resolution, one or two cells across (the corpus's), which gets four colours, wider
// strips and blocks weighing their tone steps.
bool small_cells_from_design(cv::Size cell, cv::Size source) {
    return std::min(cell.width, cell.height) <= kLargeCell &&
           std::min(source.width, source.height) >= CellSet::kSmallSource;
}

// Strips an eighth of the cell each side instead of a tenth, for sets of four colours or more of
// cells up to kLargeCell off a lattice, from a source of kSmallSource or more that holds an
// inside block and the wider frame. The cuts of a cell's blocks into its strips then wander
// over a deeper band, and the line of strip between the cuts on either side of a border shows
// less (sessions 40-41: with three colours, a sixth brought lines along the grid down on
// every design tried, but a strip at one edge in nine was more of the wall: granite's
// periodicity 0.69 -> 1.40). With four, a strip shows at one edge in 16. The corpus at map
// seeds 1 and 2 against three colours and a tenth (session 42; lines / texture energy against
// quilting's): granite 1.20 -> 1.14, limestone 1.19 / 1.11 -> 1.12 / 1.15 and 1.20 / 1.08 ->
// 1.19 / 1.16, slate 1.25 -> 1.21 and 1.24, wood 1.69 -> 1.54, 1.68 -> 1.65, marble 1.15 ->
// 1.16 and 1.15. A sixth: slate 1.14 and 1.22, wood 1.45 and 1.47, granite 1.11, but
// limestone's texture energy 1.23 and 1.21 (over its gate); a seventh: limestone 1.21.
constexpr int kWideFrameParts = 8;
bool wide_frame(int k, cv::Size cell, cv::Size source, bool lattice) {
    const cv::Size least = least_source(cell, frame_width(cell, kWideFrameParts));
    return k >= 4 && !lattice && small_cells_from_design(cell, source) &&
           source.width >= least.width && source.height >= least.height;
}

}  // namespace

cv::Size CellSet::smallest_source(cv::Size cell) {
    // An inside block (three quarters of the cell, below) and the frame: a strip longer than
    // the source is quilted from two blocks. Until session 27 a set needed the whole strip in
    // one block, a cell and its frame, and an exemplar of the cell's side (the demo design at
    // 100 dpi: 256 px, cells of 256) was first quilted to twice the cell. The set then copied
    // a quilt's shards and seams, never the stone: texture energy 1.92-2.07 times quilting's
    // at map seeds 1-4 (coherence 1.64, completeness 1.64 against 0.95 and 0.63 at seed 1).
    // From the exemplar itself, with the smaller inside blocks below: 1.00-1.16.
    return least_source(cell, frame_width(cell));
}

int CellSet::frame_for(int corner_colours, cv::Size cell, cv::Size source, bool lattice) {
    return frame_width(
        cell, wide_frame(corner_colours, cell, source, lattice) ? kWideFrameParts : kFrameParts);
}

int CellSet::default_corner_colours(cv::Size cell, cv::Size source) {
    if (slab_scan(cell, source)) return 3;
    const int source_side = std::min(source.width, source.height);
    if (source_side < kSmallSource / 2) return 4;
    if (std::min(cell.width, cell.height) > kLargeCell) return 2;
    return source_side >= kSmallSource && source_side < 2 * kSmallSource ? 4 : 3;
}

int CellSet::default_variants(int corner_colours, cv::Size cell, cv::Size source) {
    const int side = std::min(cell.width, cell.height);
    if (corner_colours >= 4 && small_cells_from_design(cell, source)) return 1;
    const bool two =
        large_cells(corner_colours, cell, source) || side <= kLargeCell || corner_colours == 2;
    return two ? 2 : 1;
}

bool CellSet::slab_scan(cv::Size cell, cv::Size source) {
    constexpr double kThreeColourImages = 81;
    return kThreeColourImages * cell.area() < double(source.area());
}

CellSet::CellSet(const cv::Mat& source_rgb, const cv::Mat& source_lab, const CellSetParams& params)
    : source_rgb_(source_rgb),
      source_lab_(source_lab),
      params_(params),
      k_(params.corner_colours),
      cw_(params.cell.width),
      ch_(params.cell.height) {
    if (k_ < 2) throw SynthError("a cell set needs at least 2 corner colours");
    const int side = std::min(cw_, ch_);
    // Measured on the corpus by eye and by texture energy both ways (texture_energy.hpp):
    //  - every seam costs: an 8 px neighbourhood across a cut is nowhere in the exemplar, and
    //    a heat map of that distance over a render shows nothing but the cuts. So cells are
    //    quilted with blocks of three quarters of the cell each way, overlapping by a quarter
    //    of a block: two blocks across, where blocks of half a cell overlapping by half a block
    //    made three, and a seam every 40 px (gravel 1.77 times quilting's texture energy, 1.70
    //    with these blocks; limestone 1.86, 1.71). Quarter-cell blocks chopped veins and grains
    //    into squares. The usage cost below keeps large blocks from repeating the same few
    //    best matches in cell after cell;
    //  - a strip is one block, its corner cores aside: strips quilted from blocks of a quarter
    //    cell put a cut across every cell border every 24 px (gravel 1.68 against 1.70);
    //  - the frame is a tenth of the cell: with a sixteenth, the cuts of the two cells on
    //    either side of an edge ran a few pixels apart and drew a line of strip along every
    //    cell border; with an eighth, the strips (the same at one edge in K^2) were so much of
    //    the plane that fine granite repeated with them (periodicity 1.9 against 0.9). Only
    //    its outer pixel is locked; the cells' own blocks take its inner part (kept_depths())
    //    and cut into the rest;
    //  - the corner blocks are small cores (a third of the frame): whole 2w blocks were cut
    //    round as squares, the same square at a third of all vertices.

    // Per variant: each keeps its own account of what it copied (below).
    large_ = large_cells(k_, params.cell, source_lab.size());
    if (params.lattice) {
        // On a lattice copies move only by lattice translations: the cut needs the room of
        // blocks half a cell across overlapping by half a block to follow a course or a grout
        // line (with the larger blocks a wall of courses kept 0.796 of its course continuity,
        // under the 0.8 it keeps with these).
        block_ = cv::Size(std::max(8, side / 2), std::max(8, side / 2));
        overlap_ = std::max(2, side / 4);
    } else {
        block_ = cv::Size(std::max(8, cw_ * 3 / 4), std::max(8, ch_ * 3 / 4));
        // From a source under one and a half cells (an exemplar of about the cell's side) a
        // block of three quarters of the cell has under a quarter of the cell to move in: every
        // cell showed the source's one white vein at nearly the same place (the demo design at
        // 100 dpi, map seed 4: periodicity 1.70). Blocks of half the cell move twice as far:
        // 0.77, texture energy 1.17 and 1.16 times quilting's (map seeds 1-4: periodicity
        // 0.65-1.00, texture energy 1.00-1.16).
        if (2 * std::min(source_rgb.cols, source_rgb.rows) < 3 * side)
            block_ = cv::Size(std::max(8, cw_ / 2), std::max(8, ch_ / 2));
        overlap_ = std::max(
            2, std::min(block_.width, block_.height) / (large_ ? kLargeCellOverlapParts : 4));
    }
    w_ = frame_for(k_, params.cell, source_rgb.size(), params.lattice != nullptr);
    // One block a strip where the source has room for it (smallest_source()).
    strip_block_ =
        std::min(std::max(cw_, ch_) + 2 * w_, std::min(source_rgb.cols, source_rgb.rows) - 2);
    strip_overlap_ = std::max(2, side / 16);
    c_ = std::max(2, w_ / 3);
    if (const cv::Size least = smallest_source(params.cell);
        source_rgb.cols < least.width || source_rgb.rows < least.height)
        throw SynthError("the source is too small for a cell set of this cell size");

    cv::Scalar mean, deviation;
    cv::meanStdDev(source_lab, mean, deviation);
    const double variance = deviation.dot(deviation);
    // Squared CIELab distance from the mean, in units of the source's variance, pixel by pixel.
    cv::Mat z2;
    {
        cv::Mat difference = source_lab - mean;
        std::vector<cv::Mat> channels;
        cv::split(difference.mul(difference), channels);
        z2 = (channels[0] + channels[1] + channels[2]) / variance;
    }
    usage_weight_ = kUsageCost * variance;
    same_place_weight_ = kSamePlaceCost * variance;  // on a lattice a ban (quilt_block())
    if (large_) {
        // The same over a sixteenth of the cell, less what is still typical, times the variance:
        // a match cost per pixel.
        cv::Mat blurred;
        cv::GaussianBlur(z2, blurred, {0, 0}, std::max(1.0, side / 16.0));
        conspicuous_ = cv::max(blurred - kConspicuousZ2, 0.0) * (kConspicuousCost * variance);
        if (params.lattice) conspicuous_.setTo(0);  // grout lines are the design
    }
    if (!params.lattice && !large_ && std::max(source_lab.cols, source_lab.rows) > kCoarseSide &&
        slab_scan(params.cell, source_lab.size())) {
        coarse_factor_ =
            (std::max(source_lab.cols, source_lab.rows) + kCoarseSide - 1) / kCoarseSide;
        coarse_lab_ = coarse_source(source_lab, coarse_factor_);
    }
    if (params.weigh_tone_steps && !params.lattice && params.seam_feather == 0 &&
        small_cells_from_design(params.cell, source_lab.size()))
        tone_ = SourceTone(source_lab, std::max(1.0, side / 40.0));
    choose_corner_blocks(z2);
    const size_t kinds = size_t(k_) * size_t(k_);
    horizontal_.resize(kinds), vertical_.resize(kinds);
    horizontal_blocks_.resize(kinds), vertical_blocks_.resize(kinds);
    cv::Mat usage(source_lab.size(), CV_32F, cv::Scalar(0));
    // One after another: each strip sees what the strips before it copied.
    for (size_t i = 0; i < 2 * kinds; ++i) {
        const uint32_t a = uint32_t(i % kinds % size_t(k_)), b = uint32_t(i % kinds / size_t(k_));
        std::vector<Placement>& blocks =
            i < kinds ? horizontal_blocks_[i] : vertical_blocks_[i - kinds];
        (i < kinds ? horizontal_[i] : vertical_[i - kinds]) =
            make_strip(i < kinds, a, b, usage, blocks);
        count_uses(usage, blocks);
    }
    // Images are made in batches of a fixed size, whatever the threads, so that each avoids the
    // blocks of the batches before it and the set stays the same bytes on every machine.
    // A second variant is made as the first was, from what the strips left: its own account
    // of what it copied and of where, so that it draws on the whole source as the first did.
    // Charged for the first's copies too, or kept off the windows the first copied to the same
    // place, the demo's 32 images at 360 dpi ran out of calm places and copied its white vein in
    // straight-sided shards all over the plane. Quilted from the source turned half a turn, the
    // corpus's texture energy rose by a third (gravel lit from the other side).
    // That holds for large cells, whose block searches look at random windows of a larger
    // source. A source no larger than the search window (the corpus's 384 px) is searched whole,
    // and a second variant with a fresh account came out the first's very images: cells side by
    // side showed one image, as with one variant. There the second variant carries on from
    // the first, as images 17 to 32 of one set.
    const size_t combinations = kinds * kinds;
    // Two by default (build.hpp); one, as before twins were
    // broken, for large cells of three or more colours from a source they copy less than once
    // (slab scans over about 5800 px with 640 px cells): there, with a second variant carrying on
    // the first's account, the wall came out calmer, the stone's contrast lost (an 8192 px slab's
    // texture energy 1.64 times quilting's against 1.21 with one; why not yet known). With two
    // colours one variant leaves a twin across one edge in 16: the 4096 px slab (the demo stone
    // resampled) showed its white blob in cells one above the other, its correlation at whole
    // cells 0.082 (two variants: 0.030, texture energy 1.18 -> 1.12 times quilting's; session
    // 40), where three colours leave one in 81.
    const size_t variants =
        size_t(params.variants > 0 ? params.variants
                                   : default_variants(k_, params.cell, source_lab.size()));
    variants_ = int(variants);
    plain_in_four_ = variants == 2 && params.plain_in_four;
    images_.resize(cell_image_count(
        uint32_t(k_), uint32_t(variants),
        plain_in_four_ ? TextureMap::VariantRule::plain_in_four : TextureMap::VariantRule::hashed));
    // But the source's conspicuous features are charged for every copy any variant made: a
    // vein shows in about one image of the whole set, not one of each variant (the demo's white
    // vein stood as a straight-sided block in a second-variant image).
    std::vector<Placement> placed;
    // Every block of every variant: what no image may copy to its very place again (below).
    std::vector<Placement> earlier;
    // Accounts of their own: large cells' variants, each from what the strips left.
    const bool fresh_accounts = variants > 1 && large_;
    const cv::Mat after_strips = fresh_accounts ? usage.clone() : cv::Mat();
    cv::Mat all_uses = fresh_accounts ? usage.clone() : cv::Mat();  // else `usage` is all uses
    for (size_t variant = 0; variant < variants; ++variant) {
        if (variant > 0 && fresh_accounts) after_strips.copyTo(usage), placed.clear();
        // The plain combinations' further variants come last, with the last variant's.
        const size_t count =
            variant + 1 < variants ? combinations : images_.size() - variant * combinations;
        for (size_t begin = 0; begin < count; begin += kImageBatch) {
            const size_t end = std::min(count, begin + kImageBatch);
            const size_t first = variant * combinations + begin;
            std::vector<std::vector<Placement>> batch(end - begin);
            // No image copies an earlier one's window to its very place: where images share a
            // strip, the strip's own continuation in the source matches its frame at no cost at
            // all, the same-place cost notwithstanding, and image after image took it. Up to 61 %
            // of two images' insides were alike pixel for pixel (limestone at map seed 2, whose
            // periodicity that drew to 1.24, 0.49 with the ban).
            parallel_for(end - begin, params.threads, [&](size_t i) {
                images_[first + i] =
                    make_image(first + i, placed, usage, fresh_accounts ? all_uses : usage,
                               batch[i], &earlier);
            });
            // Images of a batch do not see each other's blocks, and where one window fitted both
            // frames best, both copied it to the same place: two of limestone's 32 images (384
            // px, map seed 1) showed one inside. One that repeats an earlier image of its batch
            // so is made again seeing its blocks, as those of the batches before. Not on a
            // lattice, where each block has few windows: re-made, the brick-course test's
            // courses stepped at cell borders (continuity 0.77, under its 0.8).
            for (size_t i = 1; i < batch.size() && !params.lattice; ++i) {
                const auto repeats_a_mate = [&](const Placement& p) {
                    for (size_t j = 0; j < i; ++j)
                        if (std::ranges::any_of(batch[j],
                                                [&](const Placement& q) { return repeats(p, q); }))
                            return true;
                    return false;
                };
                if (std::ranges::none_of(batch[i], repeats_a_mate)) continue;
                // Seen as the blocks of earlier batches are, a mate's block that fits both
                // frames far better than any other window was copied again all the same (the
                // demo design's right strip and its vein continued into two images, 128 px
                // cells, map seeds 1 and 5, once cells kept less of their frames): the
                // re-made image may not copy the mates' windows to their places at all, nor
                // those of earlier batches.
                std::vector<Placement> seen = placed, mates, banned = earlier;
                for (size_t j = 0; j < i; ++j)
                    mates.insert(mates.end(), batch[j].begin(), batch[j].end());
                seen.insert(seen.end(), mates.begin(), mates.end());
                banned.insert(banned.end(), mates.begin(), mates.end());
                batch[i].clear();
                images_[first + i] = make_image(
                    first + i, seen, usage, fresh_accounts ? all_uses : usage, batch[i], &banned);
            }
            for (const auto& b : batch) {
                unmatched_blocks_ += size_t(std::ranges::count(b, false, &Placement::matched));
                placed.insert(placed.end(), b.begin(), b.end());
                earlier.insert(earlier.end(), b.begin(), b.end());
                count_uses(usage, b);
                if (fresh_accounts) count_uses(all_uses, b);
            }
        }
    }
}

namespace {

// Blend weights of the new block, in 1/kWhole: integers, no floating-point rounding in pixels.
constexpr int kWhole = 256;

// How much of the new block each pixel shows once the cut is blended over `feather` px each
// side: pixels that must be new (unknown before) or are beyond `feather` on the new side show
// it whole, those that must stay (pinned old: locked, the rim) or are beyond `feather` on the
// old side show none of it, and the rest in proportion to their distances to the two, so the
// blend stays one-sided where the cut runs along a pinned edge (where cuts run straight).
// With no feather, the cut itself: each pixel all old or all new.
cv::Mat seam_weights(const Cut& cut, const std::vector<Pin>& pins, cv::Size size, int feather) {
    // A read-only view of the cut's row-major 0/1 pixels.
    const cv::Mat taken(size, CV_8U, const_cast<uint8_t*>(cut.take_new.data()));
    cv::Mat weights(size, CV_32S);
    if (feather == 0) {
        taken.convertTo(weights, CV_32S, kWhole);
        return weights;
    }
    // Chessboard distances, exact integers: to the nearest new pixel and the nearest old one.
    cv::Mat to_new, to_old;
    cv::distanceTransform(taken == 0, to_new, cv::DIST_C, 3);
    cv::distanceTransform(taken != 0, to_old, cv::DIST_C, 3);
    cv::Mat whole(size, CV_8U), none(size, CV_8U);
    for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x) {
            const Pin pin = pins[size_t(y) * size_t(size.width) + size_t(x)];
            const bool is_new = taken.at<uint8_t>(y, x) != 0;
            // Zero marks the pixels the distances below run to.
            whole.at<uint8_t>(y, x) =
                pin == Pin::New || (is_new && to_old.at<float>(y, x) > float(feather)) ? 0 : 255;
            none.at<uint8_t>(y, x) =
                (pin == Pin::Old && !is_new) || (!is_new && to_new.at<float>(y, x) > float(feather))
                    ? 0
                    : 255;
        }
    cv::Mat to_whole, to_none;
    cv::distanceTransform(whole, to_whole, cv::DIST_C, 3);
    cv::distanceTransform(none, to_none, cv::DIST_C, 3);
    for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x) {
            const int a = int(to_none.at<float>(y, x)), b = int(to_whole.at<float>(y, x));
            int w;
            if (a == 0)
                w = 0;
            else if (b == 0)
                w = kWhole;
            else
                w = (a * kWhole + (a + b) / 2) / (a + b);
            weights.at<int>(y, x) = w;
        }
    return weights;
}

// Mixes `w`/kWhole of the new pixel into the old one; 0 and kWhole copy exactly.
void blend_in(cv::Vec3b& rgb, cv::Vec3f& lab, cv::Vec3b new_rgb, cv::Vec3f new_lab, int w) {
    if (w == kWhole) {
        rgb = new_rgb, lab = new_lab;
    } else if (w > 0) {
        for (int c = 0; c < 3; ++c)
            rgb[c] = uint8_t((new_rgb[c] * w + rgb[c] * (kWhole - w) + kWhole / 2) / kWhole);
        lab = lab + (new_lab - lab) * (float(w) / kWhole);
    }
}

// Where `canvas`'s unknown pixels inside `rect` should copy from, and the seam: of the source
// windows that best match the known pixels there (plus the cost of copying much-used source
// again; lattice translations only on a lattice), the one whose minimum-cost cut through the
// known pixels near the unknown ones is cheapest per pixel of seam.
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
    // Sources already copied often cost more: best matches alone favour the few calm places
    // of a source that fit anything, and a set of them shows one motif over and over while
    // the source's veins and grains go missing.
    const auto add_usage_cost = [&](const cv::Rect& area, cv::Mat& penalty) {
        cv::Mat used = (*canvas.usage)(area).clone();
        count_uses(used, canvas.placed, area);
        // Uses count per pixel of the overlap (the match's sum runs over it); a conspicuous
        // pixel counts whole (it shows wherever the window's copy does).
        const double per_use = canvas.usage_weight * cv::sum(mask)[0] / double(rect.area());
        double scale = per_use;
        cv::Mat cost = used;
        if (canvas.conspicuous) {
            // Uses by other images and strips only: this canvas's own blocks are where a block
            // continuing them copies from, and a vein continued is not a vein repeated (counted,
            // they pushed blocks off the vein's continuation, and cuts ran straight across it).
            const cv::Mat& others =
                canvas.conspicuous_uses ? *canvas.conspicuous_uses : *canvas.usage;
            cost = per_use * used + (*canvas.conspicuous)(area).mul(
                                        others(area) + (canvas.conspicuous_first_charged ? 1 : 0));
            scale = 1;
        }
        cv::Mat sums;
        cv::integral(cost, sums, CV_64F);
        for (int y = 0; y < penalty.rows; ++y)
            for (int x = 0; x < penalty.cols; ++x) {
                const double s = sums.at<double>(y + rect.height, x + rect.width) -
                                 sums.at<double>(y, x + rect.width) -
                                 sums.at<double>(y + rect.height, x) + sums.at<double>(y, x);
                penalty.at<float>(y, x) = float(scale * s);
            }
    };
    // A window copied to the same place of the cell as an earlier image's block shows the same
    // texture at the same place of two cells: it costs in proportion to how much of the block
    // would coincide, falling to nothing `same_place` px off (a window's half). A hard ban of
    // those windows left no window at all for three blocks in five on the corpus's 384 px
    // designs (32 images of four blocks each), and those blocks went in at random. On a lattice
    // the ban stays, as for every set until session 24: with the cost the best-fitting copy
    // stayed among the few lattice windows a block has, cells' insides repeated with the cells,
    // and a wall of courses read as a two-way lattice (tests/synth/test_lattice.cpp).
    struct SamePlace {
        cv::Point window;  // the window that would show the earlier copy at the very same place
        double cost;       // its cost; less the farther a window is from it
    };
    std::vector<SamePlace> same_places;
    const int same_place = std::max(4, std::min(rect.width, rect.height) / 2);
    cv::Mat forbidden;
    if (canvas.banned)
        for (const Placement& p : *canvas.banned) {
            if (!share_places(p.at, rect)) continue;
            if (forbidden.empty()) forbidden = cv::Mat::zeros(source_lab.size(), CV_8U);
            const cv::Rect around(
                same_place_window(rect, p) - cv::Point(kRepeatReach - 1, kRepeatReach - 1),
                cv::Size(2 * kRepeatReach - 1, 2 * kRepeatReach - 1));
            forbidden(around & cv::Rect({0, 0}, source_lab.size())).setTo(255);
        }
    if (canvas.avoid) {
        const double full = canvas.same_place_weight * cv::sum(mask)[0];
        for (const Placement& p : *canvas.avoid) {
            const cv::Point d = p.at.tl() - rect.tl();
            if (std::max(std::abs(d.x), std::abs(d.y)) >= same_place) continue;
            if (lattice) {
                if (forbidden.empty()) forbidden = cv::Mat::zeros(source_lab.size(), CV_8U);
                const cv::Rect around(p.source - cv::Point(same_place - 1, same_place - 1),
                                      cv::Size(2 * same_place - 1, 2 * same_place - 1));
                forbidden(around & cv::Rect({0, 0}, source_lab.size())).setTo(255);
                continue;
            }
            if (full <= 0) continue;
            const double shared = double((p.at & rect).area()) / double(rect.area());
            same_places.push_back({p.source - d, full * shared});
        }
    }
    const auto add_same_place_cost = [&](const cv::Rect& area, cv::Mat& penalty) {
        for (const SamePlace& sp : same_places) {
            const cv::Point e = sp.window - area.tl();
            for (int y = std::max(0, e.y - same_place + 1);
                 y < std::min(penalty.rows, e.y + same_place); ++y)
                for (int x = std::max(0, e.x - same_place + 1);
                     x < std::min(penalty.cols, e.x + same_place); ++x) {
                    const int off = std::max(std::abs(x - e.x), std::abs(y - e.y));
                    penalty.at<float>(y, x) += float(sp.cost * (1.0 - double(off) / same_place));
                }
        }
    };
    OffsetSearch search{source_lab,
                        [&](cv::Point corner) {
                            return (forbidden.empty() || !forbidden.at<uint8_t>(corner)) &&
                                   (!lattice || lattice->allows(corner - rect.tl() - origin));
                        },
                        std::max(4, overlap / 2),
                        canvas.wide_search
                            ? std::max(kSearchWindow, 2 * std::max(rect.width, rect.height))
                            : kSearchWindow,
                        {},
                        canvas.coarse,
                        canvas.coarse_factor};
    if (canvas.usage || !same_places.empty())
        search.add_penalty = [&](const cv::Rect& area, cv::Mat& costs) {
            // Summed apart, then added to the match costs once: the float sums (and so the
            // maps' bytes) stay those of the source-sized penalty before.
            cv::Mat penalty = cv::Mat::zeros(costs.size(), CV_32F);
            if (canvas.usage) add_usage_cost(area, penalty);
            add_same_place_cost(area, penalty);
            costs += penalty;
        };
    std::vector<cv::Point> candidates;
    if (cv::countNonZero(mask) > 0)
        candidates = ranked_offsets(search, canvas.lab(rect), mask, rng, kCutCandidates);
    const bool matching = cv::countNonZero(mask) > 0, fallback = candidates.empty();
    if (candidates.empty()) {  // nothing to match yet (or no lattice offset fits): anywhere
        cv::Point corner(rng.range(0, source_lab.cols - rect.width),
                         rng.range(0, source_lab.rows - rect.height));
        if (lattice)
            corner =
                rect.tl() + origin + lattice->nearest(cv::Point2d(corner - rect.tl() - origin));
        corner.x = std::clamp(corner.x, 0, source_lab.cols - rect.width);
        corner.y = std::clamp(corner.y, 0, source_lab.rows - rect.height);
        candidates.push_back(corner);
    }
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
    // The best-matching windows, judged by the seam their cut would leave (what shows, and what
    // texture energy counts), not by the overlap's mean difference alone. Where conspicuous
    // features may come in (large cells), by its mean squared cost: a vein cut off square
    // along a block's edge is a short stretch of great cost, which the mean over the rest of
    // a long calm cut hid (the demo design at 360 dpi showed white rectangles with straight
    // sides, where with the squared cost a few white shards remain).
    const auto cost_of = [&](const Cut& c) {
        return canvas.conspicuous ? c.mean_square_cost : c.mean_cost;
    };
    const cv::Mat old_tone = canvas.tone && candidates.size() > 1
                                 ? known_tone(canvas.lab, canvas.known, rect, canvas.tone->sigma())
                                 : cv::Mat();
    const auto score = [&](const Cut& c, cv::Point corner) {
        if (old_tone.empty()) return cost_of(c);
        return cost_of(c) + kToneStepCost * seam_tone_step(c, old_tone, *canvas.tone, corner);
    };
    Cut cut;
    cv::Rect from;
    double best = 0;
    for (const cv::Point candidate : candidates) {
        const cv::Rect window(candidate, rect.size());
        Cut c = min_cut(canvas.lab(rect), source_lab(window), pins, canvas.cuts);
        const double s = score(c, candidate);
        if (from.empty() || s < best) cut = std::move(c), from = window, best = s;
    }
    canvas.placed.push_back({rect, from.tl(), !matching || !fallback});
    const int layer = int(canvas.layers.size());
    canvas.layers.push_back({&source_rgb, from.tl() - rect.tl(), rect, 1});
    const cv::Mat weights = seam_weights(cut, pins, rect.size(), canvas.feather);
    for (int y = 0; y < rect.height; ++y)
        for (int x = 0; x < rect.width; ++x) {
            const int w = weights.at<int>(y, x);
            if (w == 0) continue;
            if (2 * w >= kWhole) canvas.layer_of.at<int>(rect.y + y, rect.x + x) = layer;
            blend_in(canvas.rgb.at<cv::Vec3b>(rect.y + y, rect.x + x),
                     canvas.lab.at<cv::Vec3f>(rect.y + y, rect.x + x),
                     source_rgb.at<cv::Vec3b>(from.y + y, from.x + x),
                     source_lab.at<cv::Vec3f>(from.y + y, from.x + x), w);
            canvas.known.at<uint8_t>(rect.y + y, rect.x + x) = 255;
        }
}

// Quilts the unknown pixels of `area` in raster order with blocks of about `block` px; with
// `joints`, each row of blocks and the rows themselves meet at places of their own, each joint
// moved by up to a third of a block's step (cell_layout.hpp).
void quilt_area(Canvas& canvas, const cv::Rect& area, cv::Size block, int overlap,
                const cv::Mat& source_rgb, const cv::Mat& source_lab,
                const LatticeTranslations* lattice, cv::Point origin, Rng& rng,
                Rng* joints = nullptr) {
    // A thin strip gets blocks as tall as itself, overlapping by at most half a block.
    const int bh = std::min(block.height, area.height), bw = std::min(block.width, area.width);
    const int row_overlap = std::min(overlap, bh / 2), column_overlap = std::min(overlap, bw / 2);
    auto rows = block_spans(area.y, area.br().y, bh, row_overlap);
    const auto cols = block_spans(area.x, area.br().x, bw, column_overlap);
    if (joints) rows = jittered_spans(rows, (bh - row_overlap) / 3, *joints);
    for (const auto& [y0, y1] : rows) {
        for (const auto& [x0, x1] :
             joints ? jittered_spans(cols, (bw - column_overlap) / 3, *joints) : cols)
            quilt_block(canvas, cv::Rect(x0, y0, x1 - x0, y1 - y0), overlap, source_rgb, source_lab,
                        lattice, origin, rng);
    }
}

}  // namespace

void CellSet::choose_corner_blocks(const cv::Mat& source_z2) {
    // Spread over the source: each the farthest of a few random draws from those taken, among
    // the draws with nothing conspicuous (else the least conspicuous): a core shows whole at
    // every vertex of its colour, and the demo design's dark cores drew a dot at every other
    // vertex. Conspicuous: for large cells as their blocks see it (conspicuous_), else any
    // pixel beyond kCoreZ2; on a lattice the vertex is a grout crossing, the design.
    cv::Mat pixel_excess;
    if (conspicuous_.empty() && !params_.lattice) pixel_excess = cv::max(source_z2 - kCoreZ2, 0.0);
    const cv::Mat& excess = conspicuous_.empty() ? pixel_excess : conspicuous_;
    Rng rng(hash_combine(params_.seed, kCornerStream));
    const int x_hi = source_rgb_.cols - 2 * c_, y_hi = source_rgb_.rows - 2 * c_;
    for (int c = 0; c < k_; ++c) {
        cv::Point best(-1, -1);
        double best_distance = -1, best_conspicuous = 0;
        for (int draw = 0; draw < 32; ++draw) {
            cv::Point s(rng.range(0, x_hi), rng.range(0, y_hi));
            // On a lattice the vertex, w px inside the block, copies a lattice translation of
            // itself, as every cell corner is a lattice point.
            if (params_.lattice)
                s = params_.lattice->nearest({double(s.x + c_), double(s.y + c_)}) -
                    cv::Point(c_, c_);
            if (s.x < 0 || s.y < 0 || s.x > x_hi || s.y > y_hi) continue;
            double distance = 1e300;
            for (const cv::Point& other : corner_source_)
                distance = std::min(distance, cv::norm(s - other));
            const double conspicuous =
                excess.empty() ? 0 : cv::sum(excess(cv::Rect(s, cv::Size(2 * c_, 2 * c_))))[0];
            const bool better = best.x < 0 || (conspicuous == 0 && best_conspicuous == 0
                                                   ? distance > best_distance
                                                   : conspicuous < best_conspicuous);
            if (better) best = s, best_distance = distance, best_conspicuous = conspicuous;
        }
        if (best.x < 0) throw SynthError("no lattice-aligned corner block fits in the source");
        corner_source_.push_back(best);
    }
}

cv::Mat CellSet::make_strip(bool horizontal, uint32_t a, uint32_t b, const cv::Mat& usage,
                            std::vector<Placement>& placed) const {
    // Strip coordinates: the first vertex's block at the origin, the second's a cell further.
    const cv::Size size =
        horizontal ? cv::Size(cw_ + 2 * w_, 2 * w_) : cv::Size(2 * w_, ch_ + 2 * w_);
    Canvas canvas(size);
    const cv::Point second = horizontal ? cv::Point(cw_, 0) : cv::Point(0, ch_);
    const cv::Point core(w_ - c_, w_ - c_);  // the vertex lies w px in, c px into the core
    for (const auto& [colour, at] : {std::pair{a, core}, std::pair{b, second + core}}) {
        // The corner blocks stay whole: the four quarters around a vertex come from four
        // strips, and meet seamlessly only through the block they all hold. Where cuts are
        // blended, the block comes with a ring of what surrounds it in the source, free for the
        // strip's cut: that cut blends into the core's own surroundings, where a cut along the
        // locked core itself had nothing to blend with and drew the core as a hard square at
        // every vertex of its colour (the demo design at 360 dpi).
        const cv::Point from = corner_source_[colour];
        const int ring =
            std::min({2 * params_.seam_feather, w_ - c_ - 1, from.x, from.y,
                      source_rgb_.cols - from.x - 2 * c_, source_rgb_.rows - from.y - 2 * c_});
        const cv::Rect block(from - cv::Point(ring, ring),
                             cv::Size(2 * (c_ + ring), 2 * (c_ + ring)));
        canvas.paste(source_rgb_(block), source_lab_(block), at - cv::Point(ring, ring));
        canvas.locked(cv::Rect(at, cv::Size(2 * c_, 2 * c_))).setTo(255);
    }
    Rng rng(hash_combine(hash_combine(params_.seed, kStripStream),
                         uint64_t(horizontal) * 65536 + uint64_t(a) * uint64_t(k_) + b));
    canvas.feather = params_.seam_feather;
    canvas.cuts = params_.cuts;
    canvas.usage = &usage;
    canvas.usage_weight = usage_weight_;
    if (large_) {
        canvas.conspicuous = &conspicuous_;
        canvas.wide_search = true;
    }
    if (!tone_.empty()) canvas.tone = &tone_;
    if (!coarse_lab_.empty()) canvas.coarse = &coarse_lab_, canvas.coarse_factor = coarse_factor_;
    // The strip's top-left pixel lies (w, w) before its first vertex, a lattice point.
    quilt_area(canvas, cv::Rect({0, 0}, size), {strip_block_, strip_block_}, strip_overlap_,
               source_rgb_, source_lab_, params_.lattice, {-w_, -w_}, rng);
    placed = std::move(canvas.placed);
    return canvas.rgb;
}

cv::Mat CellSet::make_image(size_t index, const std::vector<Placement>& avoid, const cv::Mat& usage,
                            const cv::Mat& all_uses, std::vector<Placement>& placed,
                            const std::vector<Placement>* banned) const {
    const size_t k = size_t(k_), combination = cell_image_key(uint32_t(k_), index).combination;
    const uint32_t tl = uint32_t(combination % k), tr = uint32_t(combination / k % k),
                   bl = uint32_t(combination / k / k % k),
                   br = uint32_t(combination / k / k / k % k);
    Canvas canvas({cw_, ch_});
    // The frame: the cell's halves of its four strips. In each corner the horizontal and the
    // vertical strip overlap; the corner is cut between them, the horizontal one along the
    // horizontal edge and the vertical one along the vertical edge, as each neighbour across
    // those edges shows the same strip there. At the vertex both hold the corner's core.
    cv::Mat h_rgb(ch_, cw_, CV_8UC3, cv::Scalar::all(0)), v_rgb = h_rgb.clone();
    horizontal_[tl + k * tr](cv::Rect(w_, w_, cw_, w_)).copyTo(h_rgb(cv::Rect(0, 0, cw_, w_)));
    horizontal_[bl + k * br](cv::Rect(w_, 0, cw_, w_))
        .copyTo(h_rgb(cv::Rect(0, ch_ - w_, cw_, w_)));
    vertical_[tl + k * bl](cv::Rect(w_, w_, w_, ch_)).copyTo(v_rgb(cv::Rect(0, 0, w_, ch_)));
    vertical_[tr + k * br](cv::Rect(0, w_, w_, ch_)).copyTo(v_rgb(cv::Rect(cw_ - w_, 0, w_, ch_)));
    const cv::Mat h_lab = to_lab(h_rgb), v_lab = to_lab(v_rgb);
    // Layers 0-3: the top, bottom, left and right strip.
    for (const cv::Rect band : {cv::Rect(0, 0, cw_, w_), cv::Rect(0, ch_ - w_, cw_, w_)}) {
        canvas.paste(h_rgb(band), h_lab(band), band.tl());
        canvas.layer_of(band).setTo(int(canvas.layers.size()));
        canvas.layers.push_back({&h_rgb, {0, 0}, band, 0});
    }
    for (const cv::Rect band : {cv::Rect(0, 0, w_, ch_), cv::Rect(cw_ - w_, 0, w_, ch_)}) {
        canvas.paste(v_rgb(band), v_lab(band), band.tl());
        canvas.layer_of(band).setTo(int(canvas.layers.size()));
        canvas.layers.push_back({&v_rgb, {0, 0}, band, 0});
    }
    for (const bool right : {false, true})
        for (const bool bottom : {false, true}) {
            const cv::Rect corner(right ? cw_ - w_ : 0, bottom ? ch_ - w_ : 0, w_, w_);
            std::vector<Pin> pins(size_t(w_) * size_t(w_));
            for (int y = 0; y < w_; ++y)
                for (int x = 0; x < w_; ++x) {
                    // u runs from the vertical edge inwards, v from the horizontal edge.
                    const int u = right ? w_ - 1 - x : x, v = bottom ? w_ - 1 - y : y;
                    Pin& pin = pins[size_t(y) * size_t(w_) + size_t(x)];
                    if (v == 0 || u == w_ - 1)
                        pin = Pin::Old;
                    else if (u == 0 || v == w_ - 1)
                        pin = Pin::New;
                    else
                        pin = Pin::Free;
                }
            const Cut cut = min_cut(h_lab(corner), v_lab(corner), pins, params_.cuts);
            // Blended like every other cut: inside the core the two strips agree, and the cut
            // left it along the core's side as a hard line at every vertex (the demo design
            // at 360 dpi). The pinned edges keep their strips exactly.
            const cv::Mat weights = seam_weights(cut, pins, corner.size(), params_.seam_feather);
            for (int y = 0; y < w_; ++y)
                for (int x = 0; x < w_; ++x) {
                    const cv::Point at = corner.tl() + cv::Point(x, y);
                    cv::Vec3b& rgb = canvas.rgb.at<cv::Vec3b>(at);
                    cv::Vec3f& lab = canvas.lab.at<cv::Vec3f>(at);
                    rgb = h_rgb.at<cv::Vec3b>(at), lab = h_lab.at<cv::Vec3f>(at);
                    blend_in(rgb, lab, v_rgb.at<cv::Vec3b>(at), v_lab.at<cv::Vec3f>(at),
                             weights.at<int>(y, x));
                    const bool vertical = 2 * weights.at<int>(y, x) >= kWhole;
                    canvas.layer_of.at<int>(at) = vertical ? 2 + int(right) : int(bottom);
                }
        }
    // The cell's own blocks take the frame's inner part, and cut into the rest.
    const KeptDepths depths = kept_depths(w_, c_, params_.seam_feather, params_.wandering);
    Rng layout(hash_combine(hash_combine(params_.seed, kLayoutStream), index));
    const KeptFrame kept = kept_frame({cw_, ch_}, depths, layout);
    for (int y = 0; y < ch_; ++y)
        for (int x = 0; x < cw_; ++x)
            if (!kept.keeps({x, y}, {cw_, ch_})) canvas.known.at<uint8_t>(y, x) = 0;
    // The cell's outer pixels stay the strips': they meet the neighbours' across the edge. So
    // do its corners' quarters of the cores, chosen calm as they show at every vertex of their
    // colour: the blocks' cuts, run nearer the edge, took one of them for a block's white fleck.
    canvas.locked.setTo(255);
    canvas.locked(cv::Rect(1, 1, cw_ - 2, ch_ - 2)).setTo(0);
    for (const cv::Point corner : {cv::Point(0, 0), cv::Point(cw_ - c_, 0), cv::Point(0, ch_ - c_),
                                   cv::Point(cw_ - c_, ch_ - c_)})
        canvas.locked(cv::Rect(corner, cv::Size(c_, c_))).setTo(255);
    canvas.avoid = &avoid;
    canvas.banned = banned;
    canvas.feather = params_.seam_feather;
    canvas.cuts = params_.cuts;
    canvas.usage = &usage;
    canvas.usage_weight = usage_weight_;
    canvas.same_place_weight = same_place_weight_;
    if (large_) {
        canvas.conspicuous = &conspicuous_;
        canvas.conspicuous_uses = &all_uses;
        canvas.conspicuous_first_charged = false;
        canvas.wide_search = true;
    }
    if (!tone_.empty()) canvas.tone = &tone_;
    if (!coarse_lab_.empty()) canvas.coarse = &coarse_lab_, canvas.coarse_factor = coarse_factor_;
    Rng rng(hash_combine(hash_combine(params_.seed, kImageStream), index));
    quilt_area(canvas, cv::Rect(0, 0, cw_, ch_), block_, overlap_, source_rgb_, source_lab_,
               params_.lattice, {0, 0}, rng, params_.wandering ? &layout : nullptr);
    if (params_.smooth_steps)
        remove_layer_steps(canvas.rgb, canvas.layer_of, canvas.layers, canvas.locked);
    placed = std::move(canvas.placed);
    return canvas.rgb;
}

std::optional<cv::Point> CellSet::strip_offset(size_t index, CellEdge edge) const {
    if (params_.smooth_steps) return std::nullopt;
    const size_t k = size_t(k_), combination = cell_image_key(uint32_t(k_), index).combination;
    const size_t tl = combination % k, tr = combination / k % k, bl = combination / k / k % k,
                 br = combination / k / k / k % k;
    // The strip's band in the image, and where image pixels lie in strip coordinates
    // (make_image(): each strip's vertex sits w px into it).
    const bool horizontal = edge == CellEdge::top || edge == CellEdge::bottom;
    const std::vector<Placement>& blocks =
        horizontal ? horizontal_blocks_[edge == CellEdge::top ? tl + k * tr : bl + k * br]
                   : vertical_blocks_[edge == CellEdge::left ? tl + k * bl : tr + k * br];
    cv::Rect band;
    cv::Point to_strip;
    switch (edge) {
        case CellEdge::top:
            band = {0, 0, cw_, w_}, to_strip = {w_, w_};
            break;
        case CellEdge::bottom:
            band = {0, ch_ - w_, cw_, w_}, to_strip = {w_, w_ - ch_};
            break;
        case CellEdge::left:
            band = {0, 0, w_, ch_}, to_strip = {w_, w_};
            break;
        case CellEdge::right:
            band = {cw_ - w_, 0, w_, ch_}, to_strip = {w_ - cw_, w_};
            break;
    }
    const cv::Rect in_strip = band + to_strip;
    for (const Placement& b : blocks)
        if ((b.at & in_strip) == in_strip) return b.source - b.at.tl() + to_strip;
    return std::nullopt;
}

cv::Mat CellSet::neighbourhood(size_t index) const {
    const size_t k = size_t(k_), combination = cell_image_key(uint32_t(k_), index).combination;
    const uint32_t corner[2][2] = {
        {uint32_t(combination % k), uint32_t(combination / k % k)},
        {uint32_t(combination / k / k % k), uint32_t(combination / k / k / k % k)}};
    // The neighbours show the first variant (any would do: they differ inside only).
    // Vertices beyond the cell's own four take the colour of the nearest of them.
    const auto colour = [&](int vi, int vj) {
        return corner[std::clamp(vj, 0, 1)][std::clamp(vi, 0, 1)];
    };
    cv::Mat out(3 * ch_, 3 * cw_, CV_8UC3);
    for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
            const size_t m =
                i == 0 && j == 0
                    ? index
                    : colour(i, j) + k * (colour(i + 1, j) +
                                          k * (colour(i, j + 1) + k * colour(i + 1, j + 1)));
            images_[m].copyTo(out(cv::Rect((i + 1) * cw_, (j + 1) * ch_, cw_, ch_)));
        }
    return out;
}

}  // namespace tilejet::synth::detail
