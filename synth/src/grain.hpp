#pragma once

#include <opencv2/core/mat.hpp>

namespace tilejet::synth::detail {

// The size of an exemplar's largest structures, in pixels: the distance at which its luminance
// no longer resembles itself, where the autocorrelation averaged over all directions first
// falls below 0.1. On the corpus: terrazzo 4, granite 7, setts 11, limestone 18, slate 49, wood
// 51, marble 61 (its veins). At most a third of the exemplar's smaller side (what the
// autocorrelation can still see). `rgb` CV_8UC3.
double grain_size(const cv::Mat& rgb);

// The default cell side for an exemplar whose structures are `grain` px: three of them, so a
// cell holds whole veins, rounded to 32 px, from 128 to 192 px. Measured on the corpus (maps
// with defaults, tilejet eval): marble's cells of 192 px brought its texture energy from 1.28
// to 1.14 times quilting's, wood's of 160 from 1.03 to 0.92, slate's of 160 from 1.44 to 1.30;
// but cells of 64 px for the fine designs (granite, gravel, terrazzo, setts: three grains are
// 20 to 40 px) made it 1.3 to 1.5 times worse (a seam every few grains), so 128 is the least.
// Cells of 256 px (the demo stone enlarged to 512 px) took 69 s to build on 2 cores, beyond the
// 60 s a 512 px exemplar may take; 192 is the most until cell sets build faster.
int cell_side_for_grain(double grain);

}  // namespace tilejet::synth::detail
