#include "tilejet/synth/internal/colour_gain.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "tilejet/synth/error.hpp"

namespace tilejet::synth {

namespace {

// Every pixel's tile (lattice coordinates of the cell it lies in) and phase (its place within
// the tile, numbered): pixels with equal phase are a lattice translation apart.
struct TileLayout {
    cv::Mat phase, tile;  // CV_32S per pixel
    int phases = 0, tiles = 0;
    std::vector<int> tile_pixels;  // pixels of each tile in the exemplar
};

TileLayout lay_out_tiles(cv::Size size, const Lattice& l) {
    const double det = double(l.v1.x) * l.v2.y - double(l.v1.y) * l.v2.x;
    TileLayout t;
    t.phase.create(size, CV_32S);
    t.tile.create(size, CV_32S);
    std::map<std::pair<int, int>, int> phase_of, tile_of;
    for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x) {
            // Integer numerators over an integer determinant: the floor is exact.
            const int iu = int(std::floor((double(x) * l.v2.y - double(y) * l.v2.x) / det));
            const int iv = int(std::floor((double(y) * l.v1.x - double(x) * l.v1.y) / det));
            const cv::Point r =
                cv::Point(x, y) - cv::Point(iu * l.v1.x + iv * l.v2.x, iu * l.v1.y + iv * l.v2.y);
            auto [p, new_phase] = phase_of.try_emplace({r.x, r.y}, t.phases);
            if (new_phase) ++t.phases;
            auto [k, new_tile] = tile_of.try_emplace({iu, iv}, t.tiles);
            if (new_tile) ++t.tiles, t.tile_pixels.push_back(0);
            t.phase.at<int>(y, x) = p->second;
            t.tile.at<int>(y, x) = k->second;
            ++t.tile_pixels[size_t(k->second)];
        }
    return t;
}

// Kaiser's rule: the components whose variance is above the average carry structure shared
// across tiles; the many below it are each tile's own noise.
int structured_components(const cv::Mat& eigenvalues) {
    const double average = cv::mean(eigenvalues)[0];
    int k = 0;
    while (k < eigenvalues.rows && eigenvalues.at<double>(k) > average)
        ++k;
    return std::max(k, 1);
}

}  // namespace

cv::Mat apply_colour_gain(const cv::Mat& exemplar, const Lattice& lattice, double gain) {
    CV_Assert(exemplar.type() == CV_8UC3);
    if (!std::isfinite(gain) || gain < 0)
        throw SynthError("--colour-gain " + std::to_string(gain) + " must be 0 or more");
    if (lattice.kind == LatticeKind::Stochastic) {
        if (gain == 1) return exemplar.clone();
        throw SynthError(
            "--colour-gain needs a near-regular exemplar (brick, mosaic, textile); this one is "
            "stochastic: it has no lattice tiles whose colours could be made more or less alike");
    }
    if (lattice.kind == LatticeKind::Courses) {
        if (gain == 1) return exemplar.clone();
        throw SynthError(
            "--colour-gain needs a lattice of tiles; this exemplar has courses only (joints "
            "anywhere along them), so it has no tiles whose colours could be made more or less "
            "alike");
    }

    const TileLayout t = lay_out_tiles(exemplar.size(), lattice);
    const int dims = 3 * t.phases;
    cv::Mat mean(1, dims, CV_64F, cv::Scalar(0)), count(1, t.phases, CV_64F, cv::Scalar(0));
    for (int y = 0; y < exemplar.rows; ++y)
        for (int x = 0; x < exemplar.cols; ++x) {
            const int p = t.phase.at<int>(y, x);
            const cv::Vec3b c = exemplar.at<cv::Vec3b>(y, x);
            for (int k = 0; k < 3; ++k)
                mean.at<double>(3 * p + k) += c[k];
            count.at<double>(p) += 1;
        }
    for (int i = 0; i < dims; ++i)
        mean.at<double>(i) /= count.at<double>(i / 3);

    // Principal components over the whole tiles; partial ones at the edges take part below.
    std::vector<int> whole_row(size_t(t.tiles), -1);
    int whole = 0;
    for (int k = 0; k < t.tiles; ++k)
        if (t.tile_pixels[size_t(k)] == t.phases) whole_row[size_t(k)] = whole++;
    if (whole < 3)
        throw SynthError("--colour-gain: the exemplar holds " + std::to_string(whole) +
                         " whole lattice tiles; at least 3 are needed to compare their colours");
    cv::Mat data(whole, dims, CV_64F);
    for (int y = 0; y < exemplar.rows; ++y)
        for (int x = 0; x < exemplar.cols; ++x)
            if (const int row = whole_row[size_t(t.tile.at<int>(y, x))]; row >= 0) {
                const cv::Vec3b c = exemplar.at<cv::Vec3b>(y, x);
                for (int k = 0; k < 3; ++k)
                    data.at<double>(row, 3 * t.phase.at<int>(y, x) + k) = c[k];
            }
    const cv::PCA pca(data, mean, cv::PCA::DATA_AS_ROW);
    const cv::Mat basis = pca.eigenvectors.rowRange(0, structured_components(pca.eigenvalues));

    // Each tile's coordinates on the components, by least squares over the pixels it has, so
    // that partial tiles at the exemplar's edges are treated like whole ones.
    std::vector<std::vector<cv::Point>> pixels(size_t(t.tiles));
    for (int y = 0; y < exemplar.rows; ++y)
        for (int x = 0; x < exemplar.cols; ++x)
            pixels[size_t(t.tile.at<int>(y, x))].emplace_back(x, y);
    cv::Mat out(exemplar.size(), CV_8UC3);
    const double noise_gain = std::min(gain, 1.0);  // noise is never amplified
    for (const std::vector<cv::Point>& tile : pixels) {
        const int n = int(tile.size()) * 3;
        cv::Mat a(n, basis.rows, CV_64F), deviation(n, 1, CV_64F), coords;
        for (int i = 0; i < int(tile.size()); ++i) {
            const int p = t.phase.at<int>(tile[size_t(i)]);
            const cv::Vec3b c = exemplar.at<cv::Vec3b>(tile[size_t(i)]);
            for (int k = 0; k < 3; ++k) {
                deviation.at<double>(3 * i + k) = c[k] - mean.at<double>(3 * p + k);
                for (int j = 0; j < basis.rows; ++j)
                    a.at<double>(3 * i + k, j) = basis.at<double>(j, 3 * p + k);
            }
        }
        cv::solve(a, deviation, coords, cv::DECOMP_SVD);
        const cv::Mat structured = a * coords;
        for (int i = 0; i < int(tile.size()); ++i) {
            const int p = t.phase.at<int>(tile[size_t(i)]);
            cv::Vec3b& o = out.at<cv::Vec3b>(tile[size_t(i)]);
            for (int k = 0; k < 3; ++k) {
                const double s = structured.at<double>(3 * i + k);
                const double noise = deviation.at<double>(3 * i + k) - s;
                o[k] = cv::saturate_cast<uint8_t>(mean.at<double>(3 * p + k) + gain * s +
                                                  noise_gain * noise);
            }
        }
    }
    return out;
}

}  // namespace tilejet::synth
