#pragma once

#include <opencv2/core/mat.hpp>

namespace tilejet::synth::detail {

// The size of an exemplar's largest structures, in pixels: the distance at which its luminance
// no longer resembles itself, where the autocorrelation averaged over all directions first
// falls below 0.1. On the corpus: terrazzo 4, granite 7, setts 11, limestone 18, slate 49, wood
// 51, marble 61 (its veins). At most a third of the exemplar's smaller side (what the
// autocorrelation can still see). `rgb` CV_8UC3.
double grain_size(const cv::Mat& rgb);

// The default cell side for an exemplar whose structures are `grain` px: four of them, so a
// cell holds whole veins, rounded to 32 px, from 256 to 320 px (and at most the exemplar's
// side: build.cpp). Larger cells mean fewer seams, and seams are what texture energy counts
// and what shows: with the cell sets of 2 corner colours, cells of 256 px against the 128 px
// that fine designs had took gravel from 1.77 to 1.20 times quilting's texture energy and
// limestone from 1.86 to 1.14, and the blocks of 128 px that showed on limestone's walls went.
// (Earlier, cells of 64 px made fine designs 1.3 to 1.5 times worse: a seam every few grains.)
// Coarse stones get more than 256 px, so a cell still holds a few of their structures.
// Exemplars of 1024 px and more across (`exemplar_side`, the smaller side: slab scans, designs
// at 360 dpi) may have cells of up to 640 px: their veins are hundreds of px long, and in
// 320 px cells they came out chopped into a grid of cell-sized pieces (the demo stone at
// 200 dpi: 1.22 times quilting's texture energy in 320 px cells, 1.03 in 640 px ones; the
// build takes about five times as long, within the minutes a slab scan is given).
// On a `lattice` (bricks, courses, laid tiles) cells stay at three structures, 128 to 192 px:
// there copies move only by lattice translations, so a source holds few distinct blocks, and
// larger cells showed the cell's own pitch (a wall of courses in 176x199 px cells came out a
// two-way lattice, where 128x133 px cells kept its courses).
int cell_side_for_grain(double grain, bool lattice, int exemplar_side);

// How much of an exemplar's detail runs one way, from 0 (every direction alike) to 1 (every
// edge parallel): the coherence (l1 - l2) / (l1 + l2) of its structure tensor (the luminance
// gradient's outer product) averaged over the whole exemplar. On the corpus: wood 0.85 (its
// grain), the brick wall 0.67 (its courses), every other design 0.02-0.22 (marble's veins
// 0.21, slate 0.12, terrazzo 0.03). `rgb` CV_8UC3.
double grain_alignment(const cv::Mat& rgb);

// Which way that grain runs: its alignment (above) and the direction of its edges, in degrees
// from the horizontal (image rows), in [0, 180): the wood's planks 0, upright courses 90.
struct GrainDirection {
    double alignment = 0;
    double degrees = 0;
};
GrainDirection grain_direction(const cv::Mat& rgb);

}  // namespace tilejet::synth::detail
