#include "tilejet/synth/texture_energy.hpp"

#include <cmath>
#include <cstdlib>
#include <opencv2/core.hpp>
#include <opencv2/flann.hpp>
#include <thread>

#include "../lab.hpp"
#include "../mix64.hpp"
#include "parallel_for.hpp"
#include "tilejet/synth/error.hpp"

namespace tilejet::synth {

namespace {

constexpr int kDims = kEnergyPatch * kEnergyPatch * 3;
constexpr int kReducedDims = 24;
constexpr int kCandidates = 4;
constexpr int kChecks =
    32;  // kd-tree leaves searched per query: 64 costs twice as much for 3% lower energy
constexpr size_t kMaxExemplarPatches = 250000;
constexpr size_t kPcaSample = 20000;

// Writes the 8x8 patch of `lab` (CV_32FC3) at (x, y) as 192 floats.
void patch_row(const cv::Mat& lab, int x, int y, float* out) {
    for (int r = 0; r < kEnergyPatch; ++r) {
        const float* p = lab.ptr<float>(y + r) + 3 * x;
        std::copy(p, p + 3 * kEnergyPatch, out + r * 3 * kEnergyPatch);
    }
}

}  // namespace

struct TextureEnergy::Index {
    cv::Mat patches;  // exemplar patches, one per row, 192 floats
    cv::PCA pca;
    cv::Mat reduced;
    // One kd-forest per thread: FLANN does not promise that searches share an index safely.
    std::vector<std::unique_ptr<cv::flann::Index>> forests;
};

TextureEnergy::TextureEnergy(const cv::Mat& exemplar, int threads) : index_(new Index) {
    if (exemplar.type() != CV_8UC3 || exemplar.cols < kEnergyPatch || exemplar.rows < kEnergyPatch)
        throw SynthError("texture energy needs an 8-bit RGB exemplar of at least 8x8 px");
    if (threads <= 0) threads = int(std::max(1u, std::thread::hardware_concurrency()));
    const cv::Mat lab = detail::to_lab(exemplar);
    const size_t nx = size_t(exemplar.cols - kEnergyPatch + 1);
    const size_t ny = size_t(exemplar.rows - kEnergyPatch + 1);
    int step = 1;
    while ((nx / size_t(step) + 1) * (ny / size_t(step) + 1) > kMaxExemplarPatches)
        ++step;
    std::vector<cv::Point> at;
    for (size_t y = 0; y < ny; y += size_t(step))
        for (size_t x = 0; x < nx; x += size_t(step))
            at.emplace_back(int(x), int(y));
    index_->patches.create(int(at.size()), kDims, CV_32F);
    for (size_t i = 0; i < at.size(); ++i)
        patch_row(lab, at[i].x, at[i].y, index_->patches.ptr<float>(int(i)));

    cv::Mat sample;
    const size_t every = std::max<size_t>(1, at.size() / kPcaSample);
    for (size_t i = 0; i < at.size(); i += every)
        sample.push_back(index_->patches.row(int(i)));
    index_->pca =
        cv::PCA(sample, cv::noArray(), cv::PCA::DATA_AS_ROW, std::min(kReducedDims, sample.rows));
    index_->reduced = index_->pca.project(index_->patches);
    for (int t = 0; t < threads; ++t) {
        std::srand(1);  // FLANN draws its kd-tree splits from rand(): same trees every run
        index_->forests.push_back(
            std::make_unique<cv::flann::Index>(index_->reduced, cv::flann::KDTreeIndexParams(4)));
    }
}

TextureEnergy::~TextureEnergy() = default;

double TextureEnergy::measure(const std::vector<cv::Mat>& tiles, size_t samples,
                              uint64_t seed) const {
    if (tiles.empty() || samples == 0) return 0;
    struct Sample {
        uint32_t tile;
        int x, y;
    };
    std::vector<Sample> where(samples);
    detail::Rng rng(detail::hash_combine(seed, 0xe4e2ull));
    for (Sample& s : where) {
        s.tile = uint32_t(rng.below(tiles.size()));
        const cv::Mat& t = tiles[s.tile];
        if (t.cols < kEnergyPatch || t.rows < kEnergyPatch)
            throw SynthError("texture energy needs tiles of at least 8x8 px");
        s.x = rng.range(0, t.cols - kEnergyPatch);
        s.y = rng.range(0, t.rows - kEnergyPatch);
    }
    // Queries are grouped by tile so that each tile is converted to CIELab once per chunk.
    std::sort(where.begin(), where.end(),
              [](const Sample& a, const Sample& b) { return a.tile < b.tile; });

    const size_t chunks = index_->forests.size();
    std::vector<double> sums(chunks, 0);
    detail::parallel_for(chunks, int(chunks), [&](size_t c) {
        const size_t begin = samples * c / chunks, end = samples * (c + 1) / chunks;
        if (begin == end) return;
        cv::Mat queries(int(end - begin), kDims, CV_32F);
        cv::Mat lab;
        uint32_t lab_tile = UINT32_MAX;
        for (size_t i = begin; i < end; ++i) {
            if (where[i].tile != lab_tile)
                lab = detail::to_lab(tiles[where[i].tile]), lab_tile = where[i].tile;
            patch_row(lab, where[i].x, where[i].y, queries.ptr<float>(int(i - begin)));
        }
        cv::Mat indices, dists;
        index_->forests[c]->knnSearch(index_->pca.project(queries), indices, dists, kCandidates,
                                      cv::flann::SearchParams(kChecks));
        double sum = 0;
        for (int q = 0; q < queries.rows; ++q) {
            double best = 1e300;
            for (int k = 0; k < kCandidates; ++k) {
                const int e = indices.at<int>(q, k);
                if (e < 0) continue;
                best = std::min(best,
                                cv::norm(queries.row(q), index_->patches.row(e), cv::NORM_L2SQR));
            }
            sum += std::sqrt(best / (kEnergyPatch * kEnergyPatch));
        }
        sums[c] = sum;
    });
    double total = 0;
    for (double s : sums)
        total += s;
    return total / double(samples);
}

}  // namespace tilejet::synth
