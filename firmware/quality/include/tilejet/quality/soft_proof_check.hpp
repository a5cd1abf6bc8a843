#pragma once

// Colour on the line for the quality report: how much of a wall the line's inks cannot print,
// and how far the printed tiles (as the output profile predicts them) are from the design.

#include "tilejet/colour/cmyk_transform.hpp"
#include "tilejet/quality/wall.hpp"

namespace tilejet::quality {

// A pixel is out of gamut when going RGB -> CMYK -> RGB through the profile with relative
// colorimetric intent (which clips rather than compresses) moves it by more than this
// CIEDE2000: well above what a round trip through an accurate profile adds (under 1).
inline constexpr double kOutOfGamutDeltaE = 3.0;

struct SoftProofFigures {
    double out_of_gamut_share = 0;
    double proof_delta_e2000_mean = 0;  // design vs its soft proof with the production settings
    double proof_delta_e2000_p95 = 0;
};

// Every `stride`-th pixel of every `stride`-th row of each tile is checked.
SoftProofFigures check_soft_proof(const Wall& wall, const colour::CmykTransform& production,
                                  const colour::CmykTransform& colorimetric, int stride = 4);

}  // namespace tilejet::quality
