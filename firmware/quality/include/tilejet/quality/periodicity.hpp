#pragma once

// Periodicity (docs/design.md section 8): a repeated background makes a wall look like a grid even
// where no large area repeats verbatim. Its mark is a high peak of the autocorrelation at a
// lag of a cell's size.

#include <opencv2/core/mat.hpp>

namespace tilejet::quality {

inline constexpr int kMinPeriodLag = 16;

struct AutocorrelationPeak {
    double value = 0;  // normalized cross-correlation in [-1, 1]
    cv::Point lag;     // where it is
};

// The highest local maximum of the normalized autocorrelation of `rgb` (CV_8UC3) over lags
// with max(|dx|, |dy|) >= min_lag and |dx| <= width/2, |dy| <= height/2 (so that the two
// overlapping parts cover at least a quarter of the image each). At each lag the overlap's
// two parts are compared by Pearson correlation in CIELab, channels pooled (summed
// covariances over the root of the summed variances), which is what the near-regular issue's
// GNCC does: FFT for the cross term, summed-area tables for the parts' means and energies.
// A local maximum must exceed its 8 neighbours, so the smooth fall-off of correlation near
// lag 0 does not count as a period.
AutocorrelationPeak autocorrelation_peak(const cv::Mat& rgb, int min_lag = kMinPeriodLag);

}  // namespace tilejet::quality
