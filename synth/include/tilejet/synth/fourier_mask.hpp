#pragma once

// Fractional-Fourier regular-structure masks (docs/design.md section 7): the exemplar's strongest
// periodic components, at their true (non-integer) frequencies, as a guidance channel that can
// be evaluated at any size.

#include <opencv2/core/mat.hpp>
#include <vector>

namespace tilejet::synth {

struct FourierComponent {
    cv::Point2d frequency;  // cycles per pixel along x and y; need not fall on a DFT bin
    double amplitude = 0;   // in grey levels (0..255 scale)
    double phase = 0;       // radians, of cos(2 pi (f . p) + phase) at pixel p
};

struct FourierMask {
    std::vector<FourierComponent> components;  // strongest first

    // The sum of the components' sinusoids over pixels [0, size), as CV_32F. Being a closed
    // form, it continues the exemplar's structure past its edges at any size.
    cv::Mat evaluate(cv::Size size) const;
    // evaluate() stretched to 0..255 as CV_8U (flat when there are no components).
    cv::Mat evaluate_8bit(cv::Size size) const;
};

// The `count` strongest spectral peaks of `rgb`'s lightness (CV_8UC3), each refined to a
// sub-bin frequency, with amplitude and phase measured at that frequency.
FourierMask find_fourier_mask(const cv::Mat& rgb, int count = 8);

}  // namespace tilejet::synth
