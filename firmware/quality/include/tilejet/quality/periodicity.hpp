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

// The same correlation averaged over the lags of whole cells, two cells or more and within half
// the plane each way, and over the same lags half a cell further. The highest peak of a set's
// wall over eight cells is mostly a few pairs of cells that chance made show one image (the
// demo design at 100 dpi, map seed 2: 0.17 at three cells by four, four of twenty pairs); the
// mean over all those lags is what the set does everywhere, every cell image, strip and place
// of the cell that recurs (0.047 there with two corner colours, 0.026 with three; session 39).
// Where nothing lines up with the cells both are about 0.
struct CellLagCorrelation {
    double whole_cells = 0, half_cells = 0;
    int lags = 0;  // how many lags each mean is over (0: the plane holds no lag of two cells)
};
// `plane`: CV_8UC3 R,G,B, its top-left pixel a cell corner (cell_stretch_plane()).
CellLagCorrelation cell_lag_correlation(const cv::Mat& plane, cv::Size cell);

}  // namespace tilejet::quality
