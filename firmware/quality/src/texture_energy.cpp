#include "tilejet/quality/texture_energy.hpp"

#include <cmath>
#include <cstdlib>
#include <opencv2/core.hpp>
#include <opencv2/flann.hpp>
#include <thread>

#include "tilejet/synth/error.hpp"
#include "tilejet/synth/internal/lab.hpp"
#include "tilejet/synth/internal/mix64.hpp"
#include "tilejet/synth/internal/parallel_for.hpp"

namespace tilejet::quality {

namespace {

constexpr int kDims = kEnergyPatch * kEnergyPatch * 3;
constexpr int kReducedDims = 24;
constexpr int kCandidates = 4;
constexpr int kChecks =
    32;  // kd-tree leaves searched per query: 64 costs twice as much for 3% lower energy
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
    struct At {
        uint32_t image;
        int x, y;
    };
    std::vector<cv::Mat> labs;  // the indexed images, CIELab CV_32FC3
    std::vector<At> at;         // where each indexed patch lies
    cv::PCA pca;
    cv::Mat reduced;  // one row of 24 per patch: full patches would take 768 B each
    // One kd-forest per thread: FLANN does not promise that searches share an index safely.
    std::vector<std::unique_ptr<cv::flann::Index>> forests;

    void patch(size_t i, float* out) const { patch_row(labs[at[i].image], at[i].x, at[i].y, out); }
};

TextureEnergy::TextureEnergy(const cv::Mat& exemplar, int threads)
    : TextureEnergy(std::vector<cv::Mat>{exemplar}, threads) {}

TextureEnergy::TextureEnergy(const std::vector<cv::Mat>& images, int threads, size_t max_patches)
    : index_(new Index) {
    size_t positions = 0;
    for (const cv::Mat& image : images) {
        if (image.type() != CV_8UC3 || image.cols < kEnergyPatch || image.rows < kEnergyPatch)
            throw synth::SynthError("texture energy needs 8-bit RGB images of at least 8x8 px");
        positions += size_t(image.cols - kEnergyPatch + 1) * size_t(image.rows - kEnergyPatch + 1);
    }
    if (positions == 0) throw synth::SynthError("texture energy needs an image to index");
    if (threads <= 0) threads = int(std::max(1u, std::thread::hardware_concurrency()));
    int step = 1;
    while (positions / size_t(step * step) > std::max<size_t>(1, max_patches))
        ++step;
    Index& index = *index_;
    for (uint32_t i = 0; i < images.size(); ++i) {
        index.labs.push_back(synth::detail::to_lab(images[i]));
        for (int y = 0; y <= images[i].rows - kEnergyPatch; y += step)
            for (int x = 0; x <= images[i].cols - kEnergyPatch; x += step)
                index.at.push_back({i, x, y});
    }

    cv::Mat sample;
    const size_t every = std::max<size_t>(1, index.at.size() / kPcaSample);
    for (size_t i = 0; i < index.at.size(); i += every) {
        sample.push_back(cv::Mat(1, kDims, CV_32F));
        index.patch(i, sample.ptr<float>(sample.rows - 1));
    }
    index.pca =
        cv::PCA(sample, cv::noArray(), cv::PCA::DATA_AS_ROW, std::min(kReducedDims, sample.rows));
    // Projected a slice at a time: a million full patches would take 768 MB at once.
    constexpr size_t kSlice = 65536;
    index.reduced.create(int(index.at.size()), index.pca.eigenvectors.rows, CV_32F);
    synth::detail::parallel_for(
        (index.at.size() + kSlice - 1) / kSlice, threads, [&](size_t slice) {
            const size_t begin = slice * kSlice, end = std::min(index.at.size(), begin + kSlice);
            cv::Mat full(int(end - begin), kDims, CV_32F);
            for (size_t i = begin; i < end; ++i)
                index.patch(i, full.ptr<float>(int(i - begin)));
            index.pca.project(full).copyTo(index.reduced.rowRange(int(begin), int(end)));
        });
    for (int t = 0; t < threads; ++t) {
        std::srand(1);  // FLANN draws its kd-tree splits from rand(): same trees every run
        index.forests.push_back(
            std::make_unique<cv::flann::Index>(index.reduced, cv::flann::KDTreeIndexParams(4)));
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
    synth::detail::Rng rng(synth::detail::hash_combine(seed, 0xe4e2ull));
    for (Sample& s : where) {
        s.tile = uint32_t(rng.below(tiles.size()));
        const cv::Mat& t = tiles[s.tile];
        if (t.cols < kEnergyPatch || t.rows < kEnergyPatch)
            throw synth::SynthError("texture energy needs tiles of at least 8x8 px");
        s.x = rng.range(0, t.cols - kEnergyPatch);
        s.y = rng.range(0, t.rows - kEnergyPatch);
    }
    // Queries are grouped by tile so that each tile is converted to CIELab once per chunk.
    std::sort(where.begin(), where.end(),
              [](const Sample& a, const Sample& b) { return a.tile < b.tile; });

    const size_t chunks = index_->forests.size();
    std::vector<double> sums(chunks, 0);
    synth::detail::parallel_for(chunks, int(chunks), [&](size_t c) {
        const size_t begin = samples * c / chunks, end = samples * (c + 1) / chunks;
        if (begin == end) return;
        cv::Mat queries(int(end - begin), kDims, CV_32F);
        cv::Mat lab;
        uint32_t lab_tile = UINT32_MAX;
        for (size_t i = begin; i < end; ++i) {
            if (where[i].tile != lab_tile)
                lab = synth::detail::to_lab(tiles[where[i].tile]), lab_tile = where[i].tile;
            patch_row(lab, where[i].x, where[i].y, queries.ptr<float>(int(i - begin)));
        }
        cv::Mat indices, dists;
        index_->forests[c]->knnSearch(index_->pca.project(queries), indices, dists, kCandidates,
                                      cv::flann::SearchParams(kChecks));
        double sum = 0;
        cv::Mat candidate(1, kDims, CV_32F);
        for (int q = 0; q < queries.rows; ++q) {
            double best = 1e300;
            for (int k = 0; k < kCandidates; ++k) {
                const int e = indices.at<int>(q, k);
                if (e < 0) continue;
                index_->patch(size_t(e), candidate.ptr<float>());
                best = std::min(best, cv::norm(queries.row(q), candidate, cv::NORM_L2SQR));
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

}  // namespace tilejet::quality
