#include <lcms2.h>

#include "tilejet/synth/colour_match.hpp"

namespace tilejet::synth {

// LittleCMS's, the one every colour report of tilejet uses (profile checks, soft proofs, the
// wall's mean colour); it matches Sharma, Wu and Dalal's test data (tests/quality).
double ciede2000(const LabColour& x, const LabColour& y) {
    const cmsCIELab a{x.L, x.a, x.b}, b{y.L, y.a, y.b};
    return cmsCIE2000DeltaE(&a, &b, 1, 1, 1);
}

}  // namespace tilejet::synth
