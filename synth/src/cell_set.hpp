#pragma once

// A corner-coloured set of cell images (docs/design.md section 9; Lagae and Dutré 2006, "An
// alternative for Wang tiles: colored edges versus colored corners"), each image quilted.
//
// Every lattice vertex has one of K colours; a cell's image is the one made for its four
// corners' colours, so a set holds K^4 images. What two neighbouring cells share is fixed by the
// colours they share, and made once:
//  - a corner block per colour: 2w x 2w pixels of the source around the vertex;
//  - an edge strip per pair of corner colours along an edge: a 2w wide band of the source that
//    straddles the edge from one corner block to the other, cut into both (graph cut) where it
//    matches them best.
// A cell image shows the halves of its four strips and the quarters of its four corner blocks
// that lie in the cell (a frame w pixels wide), and inside it an image quilt (Efros and Freeman
// 2001): blocks drawn among the source windows that best match what is already there, frame
// included, each cut into its neighbours along a minimum-cost seam. Neighbours show the two
// halves of one continuous strip, so they meet seamlessly whatever colours the hash picks; apart
// from the thin frame, no two images share anything, so no cell image, edge or corner repeats on
// a grid, and everything is exemplar texture joined where it matches (what texture energy
// measures).

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <vector>

#include "graph_cut.hpp"
#include "lattice_alignment.hpp"
#include "seam_tone.hpp"
#include "strip_continuation.hpp"

namespace tilejet::synth::detail {

// A block quilted into a cell image: its rectangle there and where in the source it copies from.
struct Placement {
    cv::Rect at;
    cv::Point source;
    // False when the block had pixels to match and no window to match them with, and went in
    // at random.
    bool matched = true;
};

struct CellSetParams {
    cv::Size cell;
    int corner_colours = 2;  // K: K^4 combinations of corner colours
    // V images per combination, K^4 V in all (corner_colours.hpp). Each variant is quilted as
    // the first, with the same frame (its corners' strips) and its own inside. 0: 2 for cells up
    // to kLargeCell and for large cells; 1 for cells over kLargeCell from a source they copy
    // less than once (build.hpp says why), and for four colours of cells up to kLargeCell from
    // a source of kSmallSource or more (default_variants()).
    int variants = 0;
    uint64_t seed = 1;
    int threads = 0;
    // Near-regular exemplars: every block and strip copies from a lattice translation (+-3 px)
    // of where it goes, so courses and grout lines run on across blocks and cells. Null: any.
    const LatticeTranslations* lattice = nullptr;
    // How far (px) each side of a cut old and new are blended. An exemplar enlarged f times for
    // the print resolution has nothing sharper than about f px, and a one-pixel cut through it
    // shows as a straight hard line; blended over about f px it is as soft as the stone. 0: cuts
    // stay hard (exemplars at their own resolution, whose grain is as sharp as a cut).
    int seam_feather = 0;
    // Whole: every cut exact. Auto, for enlarged exemplars: large windows cut coarse to fine
    // (graph_cut.hpp), which loses nothing on a source with nothing sharper than a few px.
    CutLevels cuts = CutLevels::Whole;
    // With two variants, plain combinations (one colour at all four corners) get four
    // (TextureMap::VariantRule::plain_in_four), after the K^4 V others.
    bool plain_in_four = true;
    // How deep a cell keeps its frame strips wanders along its edges, and its inside blocks meet
    // at places of their own, image by image (cell_layout.hpp). False: straight frames and the
    // same joints in every image, as sets were made before session 32, whose cells a wall
    // showed as squares.
    bool wandering = true;
    // The tone steps where a cell image's blocks cut into its frame strips spread over its
    // insides (layer_steps.hpp).
    bool smooth_steps = false;
    // Off a lattice, for cells up to kLargeCell from a source of kSmallSource or more and cuts
    // not blended, each block takes, of its
    // best-matching windows, the one whose cut leaves the least tone step besides the least seam
    // cost (seam_tone.hpp). False: by seam cost alone, as sets were made before session 41.
    bool weigh_tone_steps = true;
};

class CellSet {
  public:
    // `source_rgb` CV_8UC3 R,G,B, at least smallest_source(params.cell);
    // `source_lab` its to_lab().
    CellSet(const cv::Mat& source_rgb, const cv::Mat& source_lab, const CellSetParams& params);
    // The smallest source a set of `cell` can be made from: an inside block (three quarters of
    // the cell), its strips' frame on both sides and a pixel of slack each way.
    static cv::Size smallest_source(cv::Size cell);
    // Whether a set of `cell` from `source` is a slab scan's: the 81 images of three corner
    // colours (one variant) still copy less than the source (from about 5800 px with 640 px
    // cells).
    static bool slab_scan(cv::Size cell, cv::Size source);
    // Half the width of a set's strips (its frame, px): a tenth of the cell, an eighth for four
    // colours or more of cells up to kLargeCell off a lattice from a source of kSmallSource or
    // more that holds an inside block and that frame (the constructor says why).
    static int frame_for(int corner_colours, cv::Size cell, cv::Size source, bool lattice);
    // Corner colours K by default (off a lattice, which keeps 2: build.cpp). 3 for slab scans:
    // 16 images held a tenth of an 8192 px slab, and its wall missed most of the stone's
    // variety. 3 for cells up to kLargeCell, the designs of a few hundred px at their own
    // resolution (session 39): their source is one or two cells across, so a block at a place
    // of the cell can only come from part of it, and the cells' contents lined up with one
    // another; with 36 images, two cells of a wall showed one image one time in 36 and shared
    // an edge's strip one time in four. The wall's autocorrelation at lags of whole cells, 0.04
    // to 0.06 on average on the corpus (0 elsewhere), fell to 0.016-0.017 with 168 images, a
    // strip at a ninth of the edges (granite, cobbles, slate, limestone), and the periodicity
    // of every corpus design and of the demo design at 100 dpi with it (slate 1.23 -> 0.98, the
    // demo design 5.74 -> 1.58 at map seed 2); texture energy no worse but on limestone (1.10
    // -> 1.18). Affordable since cell images are stored against the source (a 2 MB map, not
    // 26; cell_image_coding.hpp); builds take four times as long (384 px designs: 25-35 s).
    // Larger cells (the demo design at 360 dpi, slab scans up to about 5800 px) keep 2: their
    // sources are several cells across, and 168 images of 640 px would take four minutes.
    // 4 for sources under 128 px (pattern files): a 64 px granite crop 2.37 with 36 images,
    // 1.52 with 168, 1.10 with 520 (session 38). And since session 42, 4 (one variant, 256
    // images, strips an eighth of the cell: frame_for()) for cells up to kLargeCell from
    // sources of 256-511 px, the corpus's designs and the demo design at 100 dpi: lines along
    // the cell grid fainter on granite, limestone, slate and wood, the demo design's
    // periodicity 1.54 -> 1.21. From 512 px on, 3: four took the 512 px bench exemplar (320 px
    // cells) 66 s to build, over issue 16's minute (three: 37 s).
    static int default_corner_colours(cv::Size cell, cv::Size source);
    static constexpr int kSmallSource = 256;
    // Cells over this many px are "large" (cell_set.cpp says what changes for them; build.cpp
    // gives frame patches to grained designs up to it).
    static constexpr int kLargeCell = 320;
    // Variants per combination by default (CellSetParams::variants 0) for K `corner_colours`:
    // 2, but 1 for cells over kLargeCell of three or more colours from a source their set
    // copies less than once (the constructor says why), and 1 for four colours or more of cells
    // up to kLargeCell from sources of kSmallSource or more (a twin shows one time in 256).
    static int default_variants(int corner_colours, cv::Size cell, cv::Size source);

    size_t size() const { return images_.size(); }
    int variants() const { return variants_; }
    // Whether plain combinations have four variants (CellSetParams::plain_in_four, with two).
    bool plain_in_four() const { return plain_in_four_; }
    // Cell image tl + K tr + K^2 bl + K^3 br + K^4 variant, then the plain combinations' variants
    // 2 and 3 (cell_image_slot() of corner_colours.hpp), CV_8UC3 R,G,B.
    const cv::Mat& image(size_t index) const { return images_[index]; }

    // The plane around a cell that shows image `index`: 3 x 3 cells, the cell in the middle.
    // Exact inside the cell and along its frame; beyond, it depends on the neighbours' other
    // corners and shows one plausible choice.
    cv::Mat neighbourhood(size_t index) const;
    // Where the patches of a set's image may go, cell-relative: inside the cell. Beyond it the
    // plane shows the neighbours' images, whose patches belong to other sets: the A/B split of
    // one image's patches cannot keep an A patch of one image off a B patch of another, and
    // where two overlapped, sampling and region rendering disagreed. Cells never overlap, and
    // the frame already makes their borders seamless.
    bool may_hold_patch(int x, int y) const { return x >= 0 && y >= 0 && x < cw_ && y < ch_; }
    // Blocks of the images that went in at random (Placement::matched): none, whatever the set.
    size_t unmatched_blocks() const { return unmatched_blocks_; }
    // Where the strip along `edge` of image `index` copies from: image pixel p of the strip's
    // band shows source pixel p + offset, and the source beyond it continues the strip
    // (strip_continuation.hpp). Nothing when one window does not hold the whole strip (a
    // source too small for it), or when the image's pixels were moved off their copies.
    std::optional<cv::Point> strip_offset(size_t index, CellEdge edge) const;
    int frame() const { return w_; }

  private:
    void choose_corner_blocks(const cv::Mat& source_z2);
    cv::Mat make_strip(bool horizontal, uint32_t a, uint32_t b, const cv::Mat& usage,
                       std::vector<Placement>& placed) const;
    // Image `index`, whose blocks copy a source window of `avoid` to the same place only at a
    // cost, and one of `banned` (if any) never; its own blocks go to `placed`.
    cv::Mat make_image(size_t index, const std::vector<Placement>& avoid, const cv::Mat& usage,
                       const cv::Mat& all_uses, std::vector<Placement>& placed,
                       const std::vector<Placement>* banned = nullptr) const;

    const cv::Mat& source_rgb_;
    const cv::Mat& source_lab_;
    // The blocks each strip was quilted from, as horizontal_ and vertical_.
    std::vector<std::vector<Placement>> horizontal_blocks_, vertical_blocks_;
    CellSetParams params_;
    int k_, cw_, ch_, w_, c_, overlap_, strip_block_, strip_overlap_;
    int variants_ = 1;
    bool plain_in_four_ = false;
    cv::Size block_;  // the blocks cells are quilted with
    double usage_weight_ = 0;
    double same_place_weight_ = 0;
    // How far each source pixel stands out from the source's mean colour, as a match cost.
    cv::Mat conspicuous_;  // large cells only
    // Cells over kLargeCell that copy their source more than once: conspicuous cost, wide search.
    bool large_ = false;
    // The source made coarse_factor_ times smaller, for block searches coarse to fine (slab
    // scans, kCoarseSide), or empty.
    cv::Mat coarse_lab_;
    int coarse_factor_ = 1;
    SourceTone tone_;  // what blocks' tone steps are measured against, or empty
    std::vector<cv::Point> corner_source_;  // per colour: the source of its block's top-left
    // Per edge kind a + K b, R,G,B: horizontal strips (Cx + 2w) x 2w from the left vertex a's
    // block to the right vertex b's, vertical ones 2w x (Cy + 2w) from top a to bottom b.
    std::vector<cv::Mat> horizontal_, vertical_;
    std::vector<cv::Mat> images_;
    size_t unmatched_blocks_ = 0;
};

}  // namespace tilejet::synth::detail
