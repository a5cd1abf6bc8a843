#pragma once

// The tone step a cut leaves (docs/design.md section 9). A block's cut runs where old and new
// agree pixel by pixel, but two copies of a grained stone can agree in detail along a cut and
// still differ in tone by a few units of CIELab on either side of it: from a few steps back, a
// person sees that step and not the detail, and where it lies along every cell's frame the
// wall shows its cells as squares (`tilejet eval`'s lines along the cell grid).

#include <opencv2/core.hpp>

#include "graph_cut.hpp"

namespace tilejet::synth::detail {

// A source's tone: its CIELab blurred over `sigma` px, kept every `step()` px (about half the
// blur: the tone of an 8192 px slab scan costs a sixty-fourth of its source).
class SourceTone {
  public:
    SourceTone() = default;
    SourceTone(const cv::Mat& source_lab, double sigma);

    bool empty() const { return small_.empty(); }
    double sigma() const { return sigma_; }
    int step() const { return step_; }
    // The tone at source pixel `p` (the nearest kept sample).
    cv::Vec3f at(cv::Point p) const {
        return small_.at<cv::Vec3f>(std::min(p.y / step_, small_.rows - 1),
                                    std::min(p.x / step_, small_.cols - 1));
    }

  private:
    cv::Mat small_;  // CV_32FC3
    int step_ = 1;
    double sigma_ = 0;
};

// The tone of what a canvas shows in `rect` (CV_32FC3, `rect`'s size): its `known` pixels
// (CV_8U, 255) of `lab` blurred over `sigma` px, the unknown ones left out of the mean.
cv::Mat known_tone(const cv::Mat& lab, const cv::Mat& known, const cv::Rect& rect, double sigma);

// The mean tone step across `cut`: over the pixels on its new side next to one on its old side,
// the CIELab distance between `old_tone` (known_tone() of the window) and the source's tone at
// the same pixel of the copy whose top-left pixel comes from `window_corner`. 0 for a cut that
// leaves no seam.
double seam_tone_step(const Cut& cut, const cv::Mat& old_tone, const SourceTone& tone,
                      cv::Point window_corner);

}  // namespace tilejet::synth::detail
