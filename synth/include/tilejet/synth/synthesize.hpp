#pragma once

// The offline synthesizers behind `tilejet synth` and map build's source enlarger: quilting
// (quilt.hpp), constrained random sampling with gap filling (rsgf.hpp) and exact neighbourhood
// matching (enm.hpp), chosen by name.

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <string_view>

namespace tilejet::synth {

enum class SynthMethod { Quilt, Rsgf, Enm };

std::string_view synth_method_name(SynthMethod method);
// "quilt", "rsgf" or "enm"; anything else is a SynthError naming `option` and the choices.
SynthMethod parse_synth_method(std::string_view text, std::string_view option = "--method");

// Largest output side; synthesis is offline but ENM's per-pixel search is not free.
inline constexpr int kMaxSynthSide = 16384;

// Synthesizes `size` from `exemplar` (CV_8UC3 R,G,B); the same seed gives the same bytes. RSGF
// detects the exemplar's lattice first. Throws SynthError (naming --size) for a size outside
// 1..kMaxSynthSide, or when the exemplar is too small for the method.
cv::Mat synthesize(const cv::Mat& exemplar, SynthMethod method, cv::Size size, uint64_t seed);

}  // namespace tilejet::synth
