#pragma once

// Offline: building a texture map from an exemplar (docs/design.md section 2).

#include <cstdint>
#include <functional>
#include <opencv2/core/mat.hpp>
#include <string_view>

#include "tilejet/synth/synthesize.hpp"
#include "tilejet/synth/texture_map.hpp"

namespace tilejet::synth {

struct BuildParams {
    int cell_size = 0;  // 0: default, from the exemplar's grain (grain.hpp)
    // Corner colours K (docs/design.md section 9): the map holds K^4 cell images, one for each
    // combination of corner colours, so that no cell image, edge or corner repeats on a grid.
    // 1: a single cell image that wraps (what maps were before cell sets).
    // 2 by measurement: 16 images of 256 px cells beat 81 of 192 px on every corpus design
    // tried (gravel 1.20 against 1.46 times quilting's texture energy, limestone 1.14 against
    // 1.54), build in a quarter of the time and a fifth of the bytes; 81 images of 256 px took
    // 61 s for a 384 px exemplar and 15 MB. The hash still picks among 16 images per cell, with
    // their own patches over them, and no grid showed on walls of either.
    // 0: the default of CellSet::default_corner_colours. 3 where 81 images still copy less
    // than the source (slab scans from about 5800 px): an 8192 px slab's texture energy 1.14
    // times quilting's against 2.40 with 16 images, which held a tenth of it (session 36). And
    // since session 39 3 for cells up to 320 px off a lattice: with 36 images the walls of
    // designs one or two cells across correlated at every lag of whole cells (0.04-0.07 on
    // average, 0.016-0.023 with 168 images; eval's periodicity over 8 cells failed on slate
    // and the demo design at 100 dpi), and the bytes that measurement above counted went when
    // cell images were stored against the source (2 MB for 168 images of 256 px). Since
    // session 42 4 (256 images, one variant, wider strips) where such a source is 256-511 px
    // (CellSet::default_corner_colours says why and where not).
    int corner_colours = 0;
    // V cell images per combination of corner colours, K^4 V in all (with 2, plain combinations
    // get 4: K^4 2 + 2 K); with 2 a cell shows one by hash, but where a neighbour has its
    // combination the one that parts them (TextureMap::VariantRule): with one,
    // about two cells in five touched a copy of themselves, the motif doubled that the eye and
    // periodicity find first (the 256 px demo design 3.22 times quilting's at map seed 1).
    // 0: default, 2, but 1 for four corner colours of cells up to 320 px from sources of 256 px
    // or more (session 42: a twin one time in 256), and for cells over 320 px of three or more
    // corner colours from a source
    // they copy less than once (slab scans over about 5800 px with 640 px cells: an 8192 px slab's
    // texture energy 1.64 times quilting's with two, 1.21 with one, its wall calmer, the stone's
    // contrast lost); with two colours two (a 4096 px slab: one left a twin across one edge in 16).
    // By measurement over four map seeds of the corpus (session 21): two variants brought the worst
    // periodicity of each design under the gate on all but marble (before, six failed, up to 3.22).
    // Fine grain (granite, gravel, terrazzo) kept one until session 24, measured when its second
    // variant was copied from what the first left of a 512 px enlargement and cut more grains;
    // copied from the design, with every block matched, one variant left granite's and terrazzo's
    // twins across a vertex whole (periodicity 2.92 and 3.61, 1.55 and 3.47 at map seeds 1 and
    // 2; 1.04 and 1.31, 0.90 and 0.59 with two), gravel's texture energy the same; but still
    // one on a lattice of fine courses, whose courses read as a two-way lattice with two.
    // Twice the build time where there are two.
    int variants = 0;
    // P per cell image: the best P candidates are kept and split into A and B.
    // 0: default (600 for a single cell image; for a set none, 32 per image when
    // active_per_cell or candidates is given).
    int patches = 0;
    int candidates = 0;  // per cell image; 0: default (40 per patch, 8 in a set)
    uint64_t seed = 1;
    int threads = 0;  // 0: all cores; the result never depends on it
    // Expected active patches per cell (eta * |set|). 0: default, 10 for one cell image; none in
    // a set, whose images vary the plane already and where every shown patch adds seams
    // (build.cpp), 4 there when patches or candidates are given (on the demo design 10 raised
    // texture energy by a fifth over 4 and made periodicity no better).
    double active_per_cell = 0;
    // Auto: detect the exemplar's lattice; when it has one, cells are a lattice-compatible
    // rectangle and every copy (quilting blocks, patches) moves by lattice translations only.
    enum class Lattice { Auto, Off } lattice = Lattice::Auto;
    // Colour-regularity gain of a near-regular exemplar's tiles (colour_gain.hpp), applied to
    // the exemplar before anything else: 0 every tile the mean tile, 1 unchanged (and no cost).
    double colour_gain = 1;
    // How an exemplar too small to copy from directly (for a set, under an inside block and its
    // frame: only with cells under 40 px; two cells for one cell image or on a lattice) is
    // enlarged into the source: quilting
    // (toroidal, lattice-aware; the default), rsgf or enm (synthesize.hpp).
    SynthMethod enlarge = SynthMethod::Quilt;
    // Recorded in the map (BuildRecord): the print resolution the exemplar has already been
    // resampled to (resample_exemplar), and the resolution it was scanned at. 0: unknown.
    double dpi = 0, exemplar_dpi = 0;
    // In a set, how deep each cell image keeps its frame strips wanders along its edges, and
    // its inside blocks meet at places of their own (docs/design.md section 9). False: straight
    // frames and the same joints in every image, as before session 32, whose cells a wall
    // showed as squares; kept to measure against.
    bool wandering_frames = true;
    // In a set, the tone steps where each cell image's blocks cut into its frame strips are
    // spread over its insides in the gradient domain: the lines along the cell grid go, and
    // the copies' exactness with them (texture energy rises; README, session 34).
    bool smooth_steps = false;
    // In a set of cells up to 320 px off a lattice, from a source of 256 px or more enlarged
    // less than twice (cuts not blended), each block takes, of its best-matching
    // windows, the one whose cut leaves the least step of tone besides the least seam cost
    // (seam_tone.hpp; session 41: slate's lines along the grid 1.34 -> 1.25). False: by seam
    // cost alone, as before; kept to measure against.
    bool weigh_tone_steps = true;
    // In a set off a lattice and without other patches, frame patches kept per edge of each
    // cell image: the strip along the edge continued into the cell from the source it was cut
    // from, to a cut of its own (docs/design.md section 9, strip_continuation.hpp). Shown by
    // hash cell by cell, they move the cut along each border to another depth in each cell,
    // where every cell's own cut into its strips runs in one thin band and draws the grid.
    // With 4 on the corpus (session 35, README) the lines along the grid fell on grained and
    // veined designs (wood 1.67 -> 1.25) and texture energy rose on fine ones (limestone 1.10
    // -> 1.21 times quilting's, over the gate; gravel 0.95 -> 1.11). So kFrameFromGrain (the
    // default): 4 for designs with a grain in cells up to 320 px (build.cpp, kGrainAlignment), none
    // for the others; 0: none. On a design whose grain runs along the rows or the columns, on
    // the two edges across it only (build.cpp, edges_across()).
    static constexpr int kFrameFromGrain = -1;
    int frame_patches = kFrameFromGrain;
    // Expected frame patches shown per cell (of up to 4 edges x frame_patches); 0: default (8).
    double frame_active = 0;
};

// Reports build progress: a stage name and how far it is (done of total).
using BuildProgress = std::function<void(std::string_view stage, size_t done, size_t total)>;

// `exemplar` is CV_8UC3 in R,G,B order. Throws SynthError on parameters it cannot honour.
TextureMap build_texture_map(const cv::Mat& exemplar, const BuildParams& params,
                             const BuildProgress& progress = {});

}  // namespace tilejet::synth
