#include "seam_tone.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace tilejet::synth::detail {

SourceTone::SourceTone(const cv::Mat& source_lab, double sigma)
    : step_(std::max(1, int(sigma / 2))), sigma_(sigma) {
    // Made smaller first, then blurred by what is left of `sigma`: a full-size blur of an 8192 px
    // slab would hold 800 MB for a moment.
    cv::Mat small = source_lab;
    if (step_ > 1)
        cv::resize(source_lab, small,
                   {(source_lab.cols + step_ - 1) / step_, (source_lab.rows + step_ - 1) / step_},
                   0, 0, cv::INTER_AREA);
    cv::GaussianBlur(small, small_, {0, 0}, std::max(0.5, sigma / step_), 0, cv::BORDER_REFLECT);
}

cv::Mat known_tone(const cv::Mat& lab, const cv::Mat& known, const cv::Rect& rect, double sigma) {
    // Blurred with what lies around the window too, as far as the blur reaches.
    const int reach = int(std::ceil(3 * sigma));
    const cv::Rect around = cv::Rect(rect.tl() - cv::Point(reach, reach),
                                     rect.size() + cv::Size(2 * reach, 2 * reach)) &
                            cv::Rect({0, 0}, lab.size());
    cv::Mat weight, weight3, sum, total;
    known(around).convertTo(weight, CV_32F, 1.0 / 255);
    cv::merge(std::vector<cv::Mat>{weight, weight, weight}, weight3);
    cv::GaussianBlur(lab(around).mul(weight3), sum, {0, 0}, sigma, 0, cv::BORDER_CONSTANT);
    cv::GaussianBlur(weight3, total, {0, 0}, sigma, 0, cv::BORDER_CONSTANT);
    const cv::Mat tone = sum / cv::max(total, 1e-3);
    return tone(cv::Rect(rect.tl() - around.tl(), rect.size())).clone();
}

double seam_tone_step(const Cut& cut, const cv::Mat& old_tone, const SourceTone& tone,
                      cv::Point window_corner) {
    const int w = old_tone.cols, h = old_tone.rows;
    const auto taken = [&](int x, int y) {
        return cut.take_new[size_t(y) * size_t(w) + size_t(x)];
    };
    double sum = 0;
    size_t seam = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!taken(x, y)) continue;
            const bool by_old = (x > 0 && !taken(x - 1, y)) || (x + 1 < w && !taken(x + 1, y)) ||
                                (y > 0 && !taken(x, y - 1)) || (y + 1 < h && !taken(x, y + 1));
            if (!by_old) continue;
            const cv::Vec3f d =
                tone.at(window_corner + cv::Point(x, y)) - old_tone.at<cv::Vec3f>(y, x);
            sum += std::sqrt(double(d.dot(d)));
            ++seam;
        }
    return seam > 0 ? sum / double(seam) : 0.0;
}

}  // namespace tilejet::synth::detail
