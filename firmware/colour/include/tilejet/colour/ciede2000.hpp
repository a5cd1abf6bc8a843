#pragma once

// The colour difference every colour report of tilejet states: the profile check, the soft
// proof and the quality report's colour match.

namespace tilejet::colour {

struct LabColour {
    double L = 0, a = 0, b = 0;
};

// CIEDE2000 colour difference (Sharma, Wu and Dalal 2005; kL = kC = kH = 1), LittleCMS's.
double ciede2000(const LabColour& x, const LabColour& y);

}  // namespace tilejet::colour
