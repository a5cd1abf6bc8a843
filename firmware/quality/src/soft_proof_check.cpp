#include "tilejet/quality/soft_proof_check.hpp"

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "tilejet/colour/ciede2000.hpp"
#include "tilejet/colour/statistics.hpp"

namespace tilejet::quality {

namespace {

cv::Mat lab_of(const cv::Mat& rgb) {
    cv::Mat unit, lab;
    rgb.convertTo(unit, CV_32FC3, 1.0 / 255.0);
    cv::cvtColor(unit, lab, cv::COLOR_RGB2Lab);
    return lab;
}

std::vector<double> delta_e2000(const cv::Mat& a_rgb, const cv::Mat& b_rgb) {
    const cv::Mat a = lab_of(a_rgb), b = lab_of(b_rgb);
    std::vector<double> out;
    out.reserve(a.total());
    for (int y = 0; y < a.rows; ++y)
        for (int x = 0; x < a.cols; ++x) {
            const cv::Vec3f p = a.at<cv::Vec3f>(y, x), q = b.at<cv::Vec3f>(y, x);
            out.push_back(colour::ciede2000({p[0], p[1], p[2]}, {q[0], q[1], q[2]}));
        }
    return out;
}

}  // namespace

SoftProofFigures check_soft_proof(const Wall& wall, const colour::CmykTransform& production,
                                  const colour::CmykTransform& colorimetric, int stride) {
    // The sampled pixels of all tiles, one row per tile.
    const int per_row = (wall.tile.width + stride - 1) / stride;
    const int per_tile = per_row * ((wall.tile.height + stride - 1) / stride);
    cv::Mat sample(int(wall.tiles.size()), per_tile, CV_8UC3);
    for (size_t t = 0; t < wall.tiles.size(); ++t) {
        cv::Vec3b* out = sample.ptr<cv::Vec3b>(int(t));
        for (int y = 0; y < wall.tile.height; y += stride)
            for (int x = 0; x < wall.tile.width; x += stride)
                *out++ = wall.tiles[t].at<cv::Vec3b>(y, x);
    }
    SoftProofFigures f;
    const std::vector<double> clipped =
        delta_e2000(sample, colorimetric.proof(colorimetric.to_cmyk(sample)));
    f.out_of_gamut_share = double(std::count_if(clipped.begin(), clipped.end(),
                                                [](double d) { return d > kOutOfGamutDeltaE; })) /
                           double(std::max<size_t>(1, clipped.size()));
    std::vector<double> proof = delta_e2000(sample, production.proof(production.to_cmyk(sample)));
    const colour::Summary s = colour::summarize(proof, 0.95);
    f.proof_delta_e2000_mean = s.mean;
    f.proof_delta_e2000_p95 = s.percentile;
    return f;
}

}  // namespace tilejet::quality
