#include "tilejet/colour/ciede2000.hpp"

#include <lcms2.h>

namespace tilejet::colour {

// LittleCMS's, the one every colour report of tilejet uses (profile checks, soft proofs, the
// wall's mean colour); it matches Sharma, Wu and Dalal's test data
// (tests/quality/test_ciede2000.cpp).
double ciede2000(const LabColour& x, const LabColour& y) {
    const cmsCIELab a{x.L, x.a, x.b}, b{y.L, y.a, y.b};
    return cmsCIE2000DeltaE(&a, &b, 1, 1, 1);
}

}  // namespace tilejet::colour
