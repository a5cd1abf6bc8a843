#include <algorithm>

#include "lab.hpp"
#include "mix64.hpp"
#include "quilting.hpp"
#include "tilejet/synth/error.hpp"
#include "tilejet/synth/quilt.hpp"

namespace tilejet::synth {

cv::Mat quilt_image(const cv::Mat& exemplar, cv::Size size, uint64_t seed, int block) {
    if (exemplar.type() != CV_8UC3) throw SynthError("quilting needs an 8-bit R,G,B exemplar");
    if (block <= 0) block = quilt_block_for_cell(std::min(exemplar.cols, exemplar.rows));
    const detail::QuiltParams params{block, std::max(2, block / 6)};
    // Quilting lays at least two blocks each way; an output smaller than that is cut from one
    // that is not.
    const cv::Size canvas(std::max(size.width, 2 * block), std::max(size.height, 2 * block));
    detail::Rng rng(detail::hash_combine(seed, 0x9a11ull));
    const cv::Mat out = detail::quilt_open(exemplar, detail::to_lab(exemplar), canvas, params, rng);
    return canvas == size ? out : out(cv::Rect({0, 0}, size)).clone();
}

}  // namespace tilejet::synth
