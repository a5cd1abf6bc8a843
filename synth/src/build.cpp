#include "tilejet/synth/build.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numeric>
#include <opencv2/core.hpp>
#include <optional>
#include <thread>

#include "block_quilting.hpp"
#include "candidate_patch.hpp"
#include "cell_set.hpp"
#include "grain.hpp"
#include "lattice_alignment.hpp"
#include "patch_overlap.hpp"
#include "pseudo_biclique.hpp"
#include "strip_continuation.hpp"
#include "tilejet/synth/error.hpp"
#include "tilejet/synth/exemplar.hpp"
#include "tilejet/synth/internal/colour_gain.hpp"
#include "tilejet/synth/internal/enm.hpp"
#include "tilejet/synth/internal/lab.hpp"
#include "tilejet/synth/internal/mix64.hpp"
#include "tilejet/synth/internal/parallel_for.hpp"
#include "tilejet/synth/internal/rsgf.hpp"
#include "tilejet/synth/lattice.hpp"
#include "tilejet/synth/map_file.hpp"

namespace tilejet::synth {

namespace {

using namespace detail;

constexpr int kCandidatesPerPatch = 40;
constexpr int kDefaultPatches = 600;
constexpr int kDefaultPatchesPerSetImage = 32;
constexpr int kCandidatesPerSetPatch = 8;
constexpr int kOffsetDrawsInSet = 24;
constexpr double kActivePerCell = 10, kActivePerSetCell = 4;
// Frame patches (strip_continuation.hpp, asked for with BuildParams::frame_patches): candidates
// per edge of each set image, and how many are shown per cell, by measurement on the corpus
// (session 35, README): with 3 kept and 3.6 shown the cut along an edge moved in a third of the
// cells and wood's lines along the grid fell from 1.67 to 1.43; with 4 and 8, in most cells,
// to 1.22-1.26.
constexpr int kFrameCandidates = 32;
constexpr double kActiveFramePatches = 8;
// Designs with a grain (wood; grain_alignment() at least kGrainAlignment) get kGrainFramePatches
// frame patches per edge unless told otherwise. Across a grain every cut shows, and the cells'
// cuts into their strips ran along the borders across it: wood's upright bands, lines along the
// cell grid 1.54 and 1.65 at map seeds 1 and 2 (session 42's defaults), 1.23 and 1.29 with
// frame patches, texture energy 0.45 -> 0.53 and 0.44 -> 0.60 times quilting's (session 43).
// The corpus's other designs measure 0.02-0.22 and stay as they were: on fine ones frame
// patches cost texture energy (limestone over its gate, session 35). Cells up to
// CellSet::kLargeCell only: on the demo design's 480 px cells at 360 dpi frame patches made
// texture energy worse (1.40 -> 1.50) and the build three times as long. On the edges across
// the grain only (edges_across(), session 44): lines 1.19 and 1.23, builds a quarter shorter.
constexpr double kGrainAlignment = 0.5;
constexpr int kGrainFramePatches = 4;
// How wide the cuts of an enlarged design are blended (session 37): over the enlargement f, but
// at most kNarrowSeamFeather px below kWideBlendsFrom. A blend mixes two grains over its width, a
// faint double image that no part of the design shows: blended over the whole enlargement (7 px
// on the demo design at 360 dpi) the cuts made half of what set the wall's texture coherence
// apart from quilting's (0.165 against 0.080; 0.121 blended over 3 px, the same map otherwise),
// and at full size 3 px drew no line along them; a 2048 px slab (8 times) measured 1.02 times
// quilting's texture energy over 3 px, 1.12 over 4 and 1.37 over 8 (coherence 0.116, 0.119,
// 0.164). Slabs enlarged 16 and 32 times (the demo stone resampled) are another matter: over
// 3 px the 4096 px slab's cuts showed as straight steps of tone, squares at wall scale (texture
// energy 1.22 against 1.18 over 16 px); over half the enlargement the 8192 px slab kept few of
// its light parts (1.68 against 1.16 over 32 px, one map seed). Those keep their blends.
constexpr int kNarrowSeamFeather = 3;
constexpr double kWideBlendsFrom = 16;
int seam_feather(double enlargement) {
    if (enlargement < 2) return 0;  // cut hard: a design at its own resolution is sharp
    if (enlargement >= kWideBlendsFrom) return int(enlargement);
    return std::min(int(enlargement), kNarrowSeamFeather);
}

// Stream ids keep the random draws of each build stage independent of one another.
enum Stream : uint64_t { kCellStream = 1, kSourceStream, kCandidateStream, kSplitStream };

void check_params(const BuildParams& p, const cv::Mat& exemplar) {
    const int smaller = std::min(exemplar.cols, exemplar.rows);
    if (p.cell_size != 0 && (p.cell_size < 16 || p.cell_size > smaller))
        throw SynthError("--cell " + std::to_string(p.cell_size) + " must be between 16 and " +
                         std::to_string(smaller) + " (the exemplar's smaller side)");
    if (p.patches != 0 && (p.patches < 2 || p.patches > 65535))
        throw SynthError("--patches " + std::to_string(p.patches) + " must be between 2 and 65535");
    if (p.corner_colours < 0 || p.corner_colours > 4)
        throw SynthError("--corner-colours " + std::to_string(p.corner_colours) +
                         " must be between 1 and 4 (0: the default)");
    if (p.variants < 0 || p.variants > 2)
        throw SynthError("--variants " + std::to_string(p.variants) + " must be 1 or 2");
    if (p.corner_colours == 1 && p.variants > 1)
        throw SynthError("--variants " + std::to_string(p.variants) +
                         " needs a cell set (--corner-colours 2 or more)");
    if (p.candidates != 0 && p.candidates < p.patches)
        throw SynthError("--candidates " + std::to_string(p.candidates) +
                         " must be at least --patches (" + std::to_string(p.patches) + ")");
    if (!(p.active_per_cell >= 0) || !std::isfinite(p.active_per_cell))
        throw SynthError("--active " + std::to_string(p.active_per_cell) +
                         " must be positive (or 0 for the default)");
    if (p.threads < 0) throw SynthError("--threads must not be negative");
    if ((p.frame_patches < 0 && p.frame_patches != BuildParams::kFrameFromGrain) ||
        p.frame_patches > 16)
        throw SynthError("--frame-patches " + std::to_string(p.frame_patches) +
                         " must be between 0 and 16");
    if (!(p.frame_active >= 0 && p.frame_active <= 64))
        throw SynthError("--frame-active " + std::to_string(p.frame_active) +
                         " must be between 0 and 64");
    if (!(p.colour_gain >= 0) || !std::isfinite(p.colour_gain))
        throw SynthError("--colour-gain " + std::to_string(p.colour_gain) + " must be 0 or more");
}

// Progress of one stage, for parallel_for; none without a listener (parallel_for then does not
// poll).
std::function<void(size_t)> stage_progress(const BuildProgress& progress, std::string_view stage,
                                           size_t total) {
    if (!progress) return {};
    return [&progress, stage, total](size_t done) { progress(stage, done, total); };
}

std::vector<Patch> best_candidates(const CandidateSpace& space, const BuildParams& params,
                                   int candidates, int threads, const BuildProgress& progress) {
    std::vector<std::optional<Patch>> found(static_cast<size_t>(candidates));
    const uint64_t stream = hash_combine(params.seed, kCandidateStream);
    parallel_for(
        found.size(), threads,
        [&](size_t i) { found[i] = make_candidate(space, hash_combine(stream, i)); },
        stage_progress(progress, "candidate patches", found.size()));

    // Best P by seam cost alone would keep only tiny patches in flat areas (short cuts there
    // are cheap) and leave the cell image showing almost everywhere. So candidates are ranked
    // within size classes (log-spaced by patch side) and each class keeps its share of the best:
    // the kept patches span sizes from a few pixels to about a third of the cell.
    constexpr int kSizeClasses = 6;
    std::vector<std::vector<Patch>> classes(kSizeClasses);
    const double log_min = std::log(2.0), log_max = std::log(3.0 * space.max_radius + 1);
    for (auto& f : found) {
        if (!f) continue;
        const double side = std::log(double(std::max(f->width, f->height)));
        const int c = std::clamp(int((side - log_min) / (log_max - log_min) * kSizeClasses), 0,
                                 kSizeClasses - 1);
        classes[size_t(c)].push_back(std::move(*f));
    }
    // Stable sorts: equal seam costs keep candidate order, so threads never change the result.
    auto by_cost = [](const Patch& a, const Patch& b) { return a.seam_cost < b.seam_cost; };
    std::vector<Patch> kept, spare;
    for (int c = 0; c < kSizeClasses; ++c) {
        auto& members = classes[size_t(c)];
        std::stable_sort(members.begin(), members.end(), by_cost);
        // Larger classes get larger shares (1 : 2 : ... : 6): they carry most of the variety.
        constexpr size_t kWeights = kSizeClasses * (kSizeClasses + 1) / 2;
        const size_t before = size_t(c) * size_t(c + 1) / 2, upto = before + size_t(c + 1);
        const size_t share =
            size_t(params.patches) * upto / kWeights - size_t(params.patches) * before / kWeights;
        for (size_t i = 0; i < members.size(); ++i)
            (i < share ? kept : spare).push_back(std::move(members[i]));
    }
    // Classes short of candidates leave room for the best of the rest.
    std::stable_sort(spare.begin(), spare.end(), by_cost);
    for (size_t i = 0; kept.size() < size_t(params.patches) && i < spare.size(); ++i)
        kept.push_back(std::move(spare[i]));
    return kept;
}

PatchSet make_set(const std::vector<Patch>& all, const std::vector<size_t>& members,
                  double active_per_cell) {
    PatchSet set;
    for (size_t m : members)
        set.patches.push_back(all[m]);
    const size_t n = set.size(), words = set.overlap_row_words();
    set.overlap_bits.assign(n * words, 0);
    for (size_t a = 0; a < n; ++a)
        for (size_t b = a + 1; b < n; ++b)
            if (patches_overlap(set.patches[a], set.patches[b], 0, 0)) {
                set.overlap_bits[a * words + b / 64] |= uint64_t(1) << (b % 64);
                set.overlap_bits[b * words + a / 64] |= uint64_t(1) << (a % 64);
            }
    set.activation_threshold = activation_threshold(active_per_cell, n);
    return set;
}

// One cell image shows wherever no patch does: on a wall it repeats every cell, so whatever it
// has in excess becomes the wall's look. Quilting favours blocks that match their neighbours well,
// which in veined stone is the calm, darker background, and a row of blocks can pick up one bright
// vein that then reads as stripes across the wall. Several quilts are therefore made and judged
// in CIELab. Colour comes first: a wall whose mean colour is off is a wrong product, so only quilts
// within kColourTolerance of the exemplar's mean qualify. Among those the one whose rows and
// columns vary least in mean lightness (the stripes) is kept; when none qualifies, the closest in
// colour. (Scoring colour and stripes as one sum picked, for the demo design, a calm quilt
// 4.9 dE2000 darker than the exemplar, as tilejet eval showed.)
struct CellImageScore {
    double colour_distance = 0;  // CIE76 between mean colours
    double stripes = 0;          // the larger standard deviation of row or column mean L*
};

CellImageScore score_cell_image(const cv::Mat& cell_lab, const cv::Scalar& exemplar_mean) {
    const cv::Scalar m = cv::mean(cell_lab);
    CellImageScore s;
    s.colour_distance = std::sqrt((m[0] - exemplar_mean[0]) * (m[0] - exemplar_mean[0]) +
                                  (m[1] - exemplar_mean[1]) * (m[1] - exemplar_mean[1]) +
                                  (m[2] - exemplar_mean[2]) * (m[2] - exemplar_mean[2]));
    cv::Mat lightness, rows, cols;
    cv::extractChannel(cell_lab, lightness, 0);
    cv::reduce(lightness, rows, 1, cv::REDUCE_AVG);
    cv::reduce(lightness, cols, 0, cv::REDUCE_AVG);
    cv::Scalar mean, row_sd, col_sd;
    cv::meanStdDev(rows, mean, row_sd);
    cv::meanStdDev(cols, mean, col_sd);
    s.stripes = std::max(row_sd[0], col_sd[0]);
    return s;
}

cv::Mat quilt_cell_image(const cv::Mat& exemplar, const cv::Mat& exemplar_lab, cv::Size cell,
                         const QuiltParams& quilt, uint64_t seed) {
    constexpr int kTrials = 24;
    constexpr double kColourTolerance = 2.0;  // CIE76: about a just-noticeable difference
    const cv::Scalar exemplar_mean = cv::mean(exemplar_lab);
    cv::Mat best;
    CellImageScore best_score;
    auto better = [&](const CellImageScore& s) {
        const bool fits = s.colour_distance <= kColourTolerance;
        const bool best_fits = best_score.colour_distance <= kColourTolerance;
        if (fits != best_fits) return fits;
        return fits ? s.stripes < best_score.stripes
                    : s.colour_distance < best_score.colour_distance;
    };
    for (int t = 0; t < kTrials; ++t) {
        Rng rng(hash_combine(hash_combine(seed, kCellStream), uint64_t(t)));
        cv::Mat candidate = quilt_toroidal(exemplar, exemplar_lab, cell, quilt, rng);
        const CellImageScore score = score_cell_image(to_lab(candidate), exemplar_mean);
        if (best.empty() || better(score)) best = candidate, best_score = score;
    }
    return best;
}

// The 3 x 3 cells around a lone cell image that wraps: what every cell of a one-image map has
// around it.
cv::Mat tiled_neighbourhood(const cv::Mat& cell) {
    cv::Mat out;
    cv::repeat(cell, 3, 3, out);
    return out;
}

// One cell image's own A and B patch sets: the best candidates cut against what the plane
// shows around the image, split so that no A patch meets a B patch in any neighbour placement.
void make_patch_sets(CellImage& image, const CandidateSpace& space, const BuildParams& params,
                     int patches, int candidates, double active_per_cell, int threads,
                     const BuildProgress& progress) {
    BuildParams per_image = params;
    per_image.patches = patches;
    const std::vector<Patch> kept =
        best_candidates(space, per_image, candidates, threads, progress);

    // Which pairs may not be split across A and B: a B cell sits left, right, above or below
    // every A cell, so a conflict is an overlap in any of those four placements.
    const int cw = int(space.grid.cell_width()), ch = int(space.grid.cell_height());
    const size_t n = kept.size();
    std::vector<uint8_t> conflict(n * n, 0);
    parallel_for(
        n, threads,
        [&](size_t u) {
            for (size_t v = 0; v < n; ++v)
                conflict[u * n + v] = patches_overlap(kept[u], kept[v], cw, 0) ||
                                      patches_overlap(kept[u], kept[v], -cw, 0) ||
                                      patches_overlap(kept[u], kept[v], 0, ch) ||
                                      patches_overlap(kept[u], kept[v], 0, -ch);
        },
        stage_progress(progress, "A/B conflicts", n));
    Rng split_rng(hash_combine(params.seed, kSplitStream));
    const BicliqueSplit split = split_pseudo_biclique(n, conflict, split_rng);
    if (split.a.empty() || split.b.empty())
        throw SynthError(
            "could not split the patches into two non-overlapping sets; "
            "try more --patches or a larger --cell");
    image.a = make_set(kept, split.a, active_per_cell);
    image.b = make_set(kept, split.b, active_per_cell);
}

// Where a set's images get frame patches, and how many per edge.
struct FramePlan {
    int per_edge = 0;
    std::vector<CellEdge> edges;
};

// A set image's frame patches (strip_continuation.hpp): along each of the plan's edges whose
// strip continues in the source, the `per_edge` best of kFrameCandidates by their seams, in
// both the image's A and its B set: they lie inside the cell, where no neighbour's patch can
// meet them.
void make_frame_patches(CellImage& image, const CellSet& set, size_t m, const cv::Mat& source_lab,
                        CutLevels cuts, const FramePlan& plan, double active_per_cell,
                        uint64_t seed, int threads) {
    const cv::Mat image_lab = to_lab(image.pixels);
    std::vector<Patch> kept;
    for (const CellEdge edge : plan.edges) {
        const std::optional<cv::Point> offset = set.strip_offset(m, edge);
        if (!offset) continue;
        const ContinuationSpace space{image_lab, source_lab, edge, *offset, set.frame(), cuts};
        std::vector<std::optional<Patch>> found(kFrameCandidates);
        const uint64_t stream = hash_combine(seed, uint64_t(edge) + 1);
        parallel_for(found.size(), threads, [&](size_t i) {
            found[i] = make_continuation(space, hash_combine(stream, i));
        });
        std::vector<Patch> along;
        for (auto& f : found)
            if (f) along.push_back(std::move(*f));
        std::stable_sort(along.begin(), along.end(),
                         [](const Patch& a, const Patch& b) { return a.seam_cost < b.seam_cost; });
        along.resize(std::min(along.size(), size_t(plan.per_edge)));
        std::ranges::move(along, std::back_inserter(kept));
    }
    if (kept.empty()) return;
    std::vector<size_t> all(kept.size());
    std::iota(all.begin(), all.end(), size_t(0));
    image.a = make_set(kept, all, active_per_cell);
    image.b = make_set(kept, all, active_per_cell);
}

// The edges whose cuts cross an exemplar's grain: a cut along a grain hides among its lines,
// one across it shows. Wood's planks run along the rows: frame patches on the upright edges
// only took its lines along the cell grid from 1.23 and 1.29 (all four edges) to 1.19 and 1.23
// at map seeds 1 and 2, and its build from 80 to 58 s; on the rows' edges only, 1.63
// (session 44). A grain within kAcrossWithin degrees of the rows or the columns gets the two
// edges across it, any other (or none) all four.
std::vector<CellEdge> edges_across(const GrainDirection& grain) {
    constexpr double kAcrossWithin = 30;
    if (grain.alignment >= kGrainAlignment) {
        if (grain.degrees < kAcrossWithin || grain.degrees > 180 - kAcrossWithin)
            return {CellEdge::left, CellEdge::right};
        if (std::abs(grain.degrees - 90) < kAcrossWithin) return {CellEdge::top, CellEdge::bottom};
    }
    return {CellEdge::top, CellEdge::bottom, CellEdge::left, CellEdge::right};
}

// A set's frame patches: as many as asked for, or by the exemplar's grain when the default is
// asked for (kGrainAlignment and beside it), on the edges across its grain. None on a lattice:
// there a cell's courses and grout lines meet its strips where the lattice puts them, and the
// brick wall was not measured with them. (Smoothed images get none either:
// CellSet::strip_offset() knows their pixels moved.)
FramePlan frame_plan_for(const BuildParams& params, bool on_lattice, int cell,
                         const cv::Mat& input) {
    if (on_lattice || params.frame_patches == 0) return {};
    const GrainDirection grain = grain_direction(input);
    if (params.frame_patches != BuildParams::kFrameFromGrain)
        return {params.frame_patches, edges_across(grain)};
    if (cell <= CellSet::kLargeCell && grain.alignment >= kGrainAlignment)
        return {kGrainFramePatches, edges_across(grain)};
    return {};
}

}  // namespace

TextureMap build_texture_map(const cv::Mat& input, const BuildParams& params,
                             const BuildProgress& progress) {
    check_exemplar(input, "exemplar");
    check_params(params, input);
    const int threads = params.threads > 0 ? params.threads
                                           : int(std::max(1u, std::thread::hardware_concurrency()));
    const int corner_colours = params.corner_colours;
    // A set shows no patches unless they are asked for. Its images vary the plane already, and
    // every shown patch is a closed seam through them: on the corpus at map seeds 1 and 2
    // (session 29) texture energy came out lower without them on all 22 (design, seed) pairs,
    // the insides' coherence about half (limestone 0.46 against 0.80), and the gates failed on
    // 4 pairs instead of 9 (README, "Session 29: no patches in a set").
    const bool shows_patches = corner_colours == 1 || params.active_per_cell > 0 ||
                               params.patches > 0 || params.candidates > 0;
    const double active_per_cell = params.active_per_cell > 0 ? params.active_per_cell
                                   : corner_colours == 1      ? kActivePerCell
                                   : shows_patches            ? kActivePerSetCell
                                                              : 0;
    // A set shares the plane out among many cell images: fewer patches each, searched less
    // widely, keep the build within a minute for a 512 px exemplar.
    const int patches = !shows_patches ? 0
                        : params.patches
                            ? params.patches
                            : (corner_colours == 1 ? kDefaultPatches : kDefaultPatchesPerSetImage);
    const int candidates =
        params.candidates
            ? params.candidates
            : (corner_colours == 1 ? kCandidatesPerPatch : kCandidatesPerSetPatch) * patches;

    // Near-regular exemplars get cells whose sides are lattice vectors, so that every cell
    // starts on the same phase of the pattern, and copies that move by lattice translations.
    // The lattice is the exemplar's geometry, which the colour gain leaves alone.
    std::optional<Lattice> detected;
    if (params.lattice == BuildParams::Lattice::Auto || params.colour_gain != 1) {
        if (progress) progress("lattice", 0, 1);
        detected = detect_lattice(input);
    }
    const cv::Mat exemplar =
        params.colour_gain == 1 ? input : apply_colour_gain(input, *detected, params.colour_gain);
    // Cells sized to the stone: a few of its largest structures across (grain.hpp), at most
    // the exemplar's smaller side (a source twice the cell is quilted from it then); fewer on a
    // lattice, which cells then follow.
    const double grain = params.cell_size ? 0 : grain_size(input);
    const auto cell_side = [&](bool on_lattice) {
        return params.cell_size ? params.cell_size
                                : std::min(cell_side_for_grain(grain, on_lattice,
                                                               std::min(input.cols, input.rows)),
                                           std::min(input.cols, input.rows));
    };
    std::optional<LatticeTranslations> lattice;
    cv::Size cell_size(cell_side(false), cell_side(false));
    if (params.lattice == BuildParams::Lattice::Auto) {
        if (detected->kind != LatticeKind::Stochastic) {
            LatticeTranslations translations(*detected);
            if (auto rect = translations.cell_size(cell_side(true), exemplar.size())) {
                lattice = translations;
                cell_size = *rect;
            }
        }
    }
    const int cell = std::min(cell_size.width, cell_size.height);

    TextureMap map;
    map.cell_width = cell_size.width;
    map.cell_height = cell_size.height;
    map.build = {params.seed,     exemplar.cols, exemplar.rows,       patches, candidates,
                 active_per_cell, params.dpi,    params.exemplar_dpi, grain};

    const cv::Mat exemplar_lab = to_lab(exemplar);
    const QuiltParams quilt{std::max(8, cell / 4), std::max(2, std::max(8, cell / 4) / 6), 0.1,
                            lattice ? &*lattice : nullptr};

    // The source is what cell images, strips and patches copy from: the exemplar itself
    // wherever it is large enough. A one-image map's patches need room around them in the
    // source: two cells. A set needs an inside block and its frame (cell_set.cpp: the demo
    // design at 100 dpi, 256 px with cells of 256, was quilted first until session 27, and
    // the set copied the quilt's shards); enlarged to two cells anyway, the
    // corpus's 384 px exemplars became quilts of their own calmest parts (marble's veins gave
    // way to rows of one small motif, limestone lost its cracks), and the set copied that
    // (docs/design.md section 2.3). On a lattice the quilt moves whole lattice periods and
    // loses little, and a source of two cells offers the cells' blocks more places in phase:
    // from a 300 px course texture itself (cells 166 px high) the courses ran on across 0.798
    // of the cell borders, under the 0.8 the lattice test asks for.
    const cv::Size needed = corner_colours == 1 || lattice
                                ? cv::Size(2 * cell_size.width, 2 * cell_size.height)
                                : CellSet::smallest_source(cell_size);
    if (exemplar.cols < needed.width || exemplar.rows < needed.height) {
        if (progress) progress("source image", 0, 1);
        Rng source_rng(hash_combine(params.seed, kSourceStream));
        // A multiple of the cell size, so that the enlargement wraps on the lattice too.
        const cv::Size enlarged(
            std::max(exemplar.cols / cell_size.width + 1, 2) * cell_size.width,
            std::max(exemplar.rows / cell_size.height + 1, 2) * cell_size.height);
        const uint64_t source_seed = hash_combine(params.seed, kSourceStream);
        switch (params.enlarge) {
            case SynthMethod::Quilt:
                map.source = quilt_toroidal(exemplar, exemplar_lab, enlarged, quilt, source_rng);
                break;
            case SynthMethod::Rsgf:
                // With --lattice off, rsgf is told there is none: blocks go anywhere.
                map.source = synthesize_rsgf(exemplar, lattice ? *detected : Lattice{}, enlarged,
                                             source_seed);
                break;
            case SynthMethod::Enm:
                map.source = synthesize_enm(exemplar, enlarged, source_seed);
                break;
        }
    } else {
        map.source = exemplar.clone();
    }
    const cv::Mat source_lab = to_lab(map.source);
    const int source_side = std::min(map.source.cols, map.source.rows);
    const CellGrid grid(cell_size.width, cell_size.height);

    if (corner_colours == 1) {
        if (progress) progress("cell image", 0, 1);
        CellImage image;
        image.pixels = quilt_cell_image(exemplar, exemplar_lab, cell_size, quilt, params.seed);
        const cv::Mat canvas = to_lab(tiled_neighbourhood(image.pixels));
        const CandidateSpace space{canvas,
                                   {cell_size.width, cell_size.height},
                                   source_lab,
                                   grid,
                                   2,
                                   std::max(2, std::min(cell / 6, (source_side / 2 - 2) * 2 / 3)),
                                   lattice ? &*lattice : nullptr,
                                   {},
                                   false,
                                   1};
        make_patch_sets(image, space, params, patches, candidates, active_per_cell, threads,
                        progress);
        map.cell_images.push_back(std::move(image));
    } else {
        if (progress) progress("cell set", 0, 1);
        // An exemplar enlarged for the print resolution: cuts blended (seam_feather()).
        const double enlargement =
            params.dpi > 0 && params.exemplar_dpi > 0 ? params.dpi / params.exemplar_dpi : 1;
        const int feather = seam_feather(enlargement);
        // Its large cuts coarse to fine: a soft source loses nothing at half resolution. Sharp
        // ones are cut exactly: on the corpus, at their own resolution, coarse-to-fine cuts
        // from 192 px (cell blocks of 256 px cells, their largest patches) cost 1 to 7 % of
        // texture energy on ten designs of eleven (docs/design.md section 2.4).
        const CutLevels cuts = enlargement >= 2 ? CutLevels::Auto : CutLevels::Whole;
        // On a lattice of fine courses (a few px, as the tests' synthetic courses) one variant,
        // as for all fine grain before session 24: with two, and every block matched, the
        // rendered courses read as a two-way lattice (tests/synth/test_lattice.cpp).
        constexpr double kFineCourses = 8;  // px: grain.hpp's measure, as before session 24
        const int variants = params.variants == 0 && lattice && grain > 0 && grain < kFineCourses
                                 ? 1
                                 : params.variants;
        const FramePlan frame_plan = frame_plan_for(params, lattice.has_value(), cell, input);
        const double frame_active =
            params.frame_active > 0 ? params.frame_active : kActiveFramePatches;
        const int kinds = corner_colours > 0 || lattice
                              ? std::max(corner_colours, 2)
                              : CellSet::default_corner_colours(cell_size, map.source.size());
        const CellSet set(
            map.source, source_lab,
            {cell_size, kinds, variants, params.seed, threads, lattice ? &*lattice : nullptr,
             feather, cuts,
             // Not on a lattice: there the plain combinations' extra variants,
             // made last, had few lattice windows left that no earlier image
             // copied to their places, and the brick wall's texture energy rose
             // (1.20 times quilting's at map seed 3 against 1.10 with two), and
             // its periodicity was 0.65-0.86 either way.
             !lattice,
             // Not on a lattice either: a wall of fine synthetic courses read as
             // a two-way lattice with wandering frames (tests/synth/
             // test_lattice.cpp), and the corpus's brick wall kept its lines
             // (1.16 / 1.37 at map seed 1 against 1.21 / 1.38 straight).
             params.wandering_frames && !lattice, params.smooth_steps, params.weigh_tone_steps});
        map.corner_colours = kinds, map.variants = set.variants();
        // A set's images copy their source block by block: stored as such, a third of the bytes.
        map.cell_storage = TextureMap::CellStorage::against_source;
        if (map.variants > 1)
            map.variant_rule = set.plain_in_four() ? TextureMap::VariantRule::plain_in_four
                                                   : TextureMap::VariantRule::hashed;
        // Patches as large as a third of the cell where their seams are good: the size classes
        // of best_candidates keep the large ones that fit.
        const int max_radius = std::max(2, std::min(cell / 3, (source_side / 2 - 2) * 2 / 3));
        for (size_t m = 0; m < set.size(); ++m) {
            if (progress) progress("cell images", m, set.size());
            CellImage image;
            image.pixels = set.image(m).clone();
            if (patches == 0) {  // no candidate patches: the image alone, or its frame patches
                if (frame_plan.per_edge > 0)
                    make_frame_patches(image, set, m, source_lab, cuts, frame_plan, frame_active,
                                       hash_combine(params.seed, m), threads);
                map.cell_images.push_back(std::move(image));
                continue;
            }
            const cv::Mat canvas = to_lab(set.neighbourhood(m));
            const CandidateSpace space{canvas,
                                       {cell_size.width, cell_size.height},
                                       source_lab,
                                       grid,
                                       2,
                                       max_radius,
                                       lattice ? &*lattice : nullptr,
                                       [&set](int x, int y) { return set.may_hold_patch(x, y); },
                                       true,
                                       kOffsetDrawsInSet,
                                       cuts};
            BuildParams per_image = params;
            per_image.seed = hash_combine(params.seed, m);
            make_patch_sets(image, space, per_image, patches, candidates, active_per_cell, threads,
                            {});
            map.cell_images.push_back(std::move(image));
        }
        if (progress) progress("cell images", set.size(), set.size());
    }
    assign_map_id(map);
    return map;
}

}  // namespace tilejet::synth
