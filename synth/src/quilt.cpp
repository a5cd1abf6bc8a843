#include "tilejet/synth/quilt.hpp"

#include <algorithm>

#include "block_quilting.hpp"
#include "tilejet/synth/error.hpp"
#include "tilejet/synth/internal/lab.hpp"
#include "tilejet/synth/internal/mix64.hpp"

namespace tilejet::synth {

int quilt_block_for_cell(int cell) {
    return std::max(8, cell / 4);
}

QuiltedImage quilt_texture(const cv::Mat& exemplar, cv::Size size, uint64_t seed, int block) {
    if (exemplar.type() != CV_8UC3) throw SynthError("quilting needs an 8-bit R,G,B exemplar");
    if (int64_t(exemplar.total()) > (int64_t(1) << 31) - 1)
        throw SynthError("quilting provenance holds exemplars of up to 2^31 pixels");
    if (block <= 0) block = quilt_block_for_cell(std::min(exemplar.cols, exemplar.rows));
    const detail::QuiltParams params{block, std::max(2, block / 6)};

    // quilt_toroidal chooses blocks by the Lab image alone and copies bytes from the image it
    // is given, so quilting an image of pixel indices yields the provenance of every pixel;
    // the colours then follow by lookup. One quilt, both results, exactly consistent. Three
    // bytes hold the indices of 2^24 pixels (a 4096 px exemplar); a larger one (a slab scan,
    // up to 8192 px) is quilted a second time, the same choices from the same seed, with the
    // indices' higher bits.
    const cv::Mat lab = detail::to_lab(exemplar);
    const auto quilt_indices = [&](int shift) {
        cv::Mat index_image(exemplar.size(), CV_8UC3);
        for (int y = 0; y < exemplar.rows; ++y)
            for (int x = 0; x < exemplar.cols; ++x) {
                const uint64_t i = (uint64_t(y) * uint64_t(exemplar.cols) + uint64_t(x)) >> shift;
                index_image.at<cv::Vec3b>(y, x) = {uint8_t(i), uint8_t(i >> 8), uint8_t(i >> 16)};
            }
        detail::Rng rng(detail::hash_combine(seed, 0x9017ull));
        return detail::quilt_toroidal(index_image, lab, size, params, rng);
    };
    const cv::Mat low = quilt_indices(0);
    const bool large = int64_t(exemplar.total()) > (int64_t(1) << 24);
    const cv::Mat high = large ? quilt_indices(24) : cv::Mat();

    QuiltedImage out{cv::Mat(size, CV_8UC3), cv::Mat(size, CV_32S)};
    for (int y = 0; y < size.height; ++y) {
        const cv::Vec3b* q = low.ptr<cv::Vec3b>(y);
        const cv::Vec3b* h = large ? high.ptr<cv::Vec3b>(y) : nullptr;
        int32_t* prov = out.provenance.ptr<int32_t>(y);
        cv::Vec3b* rgb = out.rgb.ptr<cv::Vec3b>(y);
        for (int x = 0; x < size.width; ++x) {
            const int32_t i = int32_t(q[x][0] | (q[x][1] << 8) | (q[x][2] << 16) |
                                      (h ? int32_t(h[x][0]) << 24 : 0));
            prov[x] = i;
            rgb[x] = exemplar.at<cv::Vec3b>(i / exemplar.cols, i % exemplar.cols);
        }
    }
    return out;
}

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
