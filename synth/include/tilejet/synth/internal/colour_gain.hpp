#pragma once

// Colour-regularity gain (docs/design.md section 7): how much the tiles of a near-regular exemplar
// (bricks, mosaic stones) differ in colour from one another, turned up or down.

#include <opencv2/core/mat.hpp>

#include "tilejet/synth/lattice.hpp"

namespace tilejet::synth {

// Rebuilds `exemplar` (CV_8UC3 R,G,B) with its lattice tiles' colour variation scaled by
// `gain`: 0 makes every tile the mean tile, 1 returns the exemplar unchanged, above 1 the tiles
// differ more. Tiles are the lattice's cells (pixels a lattice translation apart are the same
// place of a tile); a principal component analysis over the whole tiles separates the
// variation they share a pattern in (a tile's colour cast, a darker brick) from per-pixel noise,
// and only the former is amplified. Throws SynthError, naming --colour-gain, for a negative
// gain, a stochastic lattice with a gain other than 1, or too few whole tiles.
cv::Mat apply_colour_gain(const cv::Mat& exemplar, const Lattice& lattice, double gain);

}  // namespace tilejet::synth
