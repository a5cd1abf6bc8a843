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

// Squared distance between the 8x8 patch of `lab` at (x, y) and `patch` (192 floats).
double patch_distance(const cv::Mat& lab, int x, int y, const float* patch) {
    double sum = 0;
    for (int r = 0; r < kEnergyPatch; ++r) {
        const float* p = lab.ptr<float>(y + r) + 3 * x;
        const float* q = patch + r * 3 * kEnergyPatch;
        for (int i = 0; i < 3 * kEnergyPatch; ++i) {
            const double d = double(p[i]) - double(q[i]);
            sum += d * d;
        }
    }
    return sum;
}

}  // namespace

struct TextureEnergy::Index {
    struct At {
        uint32_t image;
        int x, y;
    };
    std::vector<cv::Mat> labs;  // the indexed images, CIELab CV_32FC3
    std::vector<At> at;         // where each indexed patch lies
    int step = 1;               // the grid of indexed positions
    cv::PCA pca;
    cv::Mat reduced;  // one row of 24 per patch: full patches would take 768 B each
    // One kd-forest, searched from every thread: OpenCV's FLANN keeps each search's heap in a
    // pool keyed by thread (flann/heap.h, getPooledInstance) and leaves the trees untouched.
    // A forest per thread, as up to session 26, cost a second build of the same trees.
    std::unique_ptr<cv::flann::Index> forest;
    int threads = 1;

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
    index.step = step;
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
    // FLANN shuffles with OpenCV's per-thread generator (cv::randShuffle) and splits with
    // rand(): both seeded here so the trees, and the figures, are the same every run.
    const cv::RNG callers = cv::theRNG();
    cv::theRNG() = cv::RNG(1);
    std::srand(1);
    index.forest =
        std::make_unique<cv::flann::Index>(index.reduced, cv::flann::KDTreeIndexParams(4));
    cv::theRNG() = callers;
    index.threads = threads;
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

    // On a grid of every `step` positions an exemplar patch copied off the grid would meet
    // only misaligned neighbours. So each sample is searched for at the step x step positions
    // from it, one of which lies on the grid wherever the copy is, and each candidate found
    // is moved back by the same shift and measured against the sample itself.
    const Index& index = *index_;
    const int step = index.step;
    const int shifts = step * step;
    constexpr size_t kBatch = 2048;  // samples searched at once: bounds the query matrix
    const size_t chunks = size_t(index.threads);
    std::vector<double> sums(chunks, 0);
    synth::detail::parallel_for(chunks, int(chunks), [&](size_t c) {
        const size_t begin = samples * c / chunks, end = samples * (c + 1) / chunks;
        cv::Mat lab;
        uint32_t lab_tile = UINT32_MAX;
        std::vector<cv::Point> shift_of;
        for (size_t batch = begin; batch < end; batch += kBatch) {
            const size_t n = std::min(kBatch, end - batch);
            cv::Mat queries(int(n) * shifts, kDims, CV_32F);
            shift_of.assign(n * size_t(shifts), cv::Point(0, 0));
            for (size_t i = 0; i < n; ++i) {
                const Sample& s = where[batch + i];
                if (s.tile != lab_tile)
                    lab = synth::detail::to_lab(tiles[s.tile]), lab_tile = s.tile;
                for (int k = 0; k < shifts; ++k) {
                    // Shifted forwards, or backwards at the tile's far edge; unshifted if the
                    // tile has no room either way.
                    cv::Point d(k % step, k / step);
                    if (s.x + d.x > lab.cols - kEnergyPatch) d.x = s.x - d.x >= 0 ? -d.x : 0;
                    if (s.y + d.y > lab.rows - kEnergyPatch) d.y = s.y - d.y >= 0 ? -d.y : 0;
                    shift_of[i * size_t(shifts) + size_t(k)] = d;
                    patch_row(lab, s.x + d.x, s.y + d.y, queries.ptr<float>(int(i) * shifts + k));
                }
            }
            cv::Mat indices, dists;
            index.forest->knnSearch(index.pca.project(queries), indices, dists, kCandidates,
                                    cv::flann::SearchParams(kChecks));
            for (size_t i = 0; i < n; ++i) {
                const float* sample = queries.ptr<float>(int(i) * shifts);  // shift (0, 0)
                double best = 1e300;
                for (int k = 0; k < shifts; ++k) {
                    const int q = int(i) * shifts + k;
                    const cv::Point d = shift_of[size_t(q)];
                    for (int j = 0; j < kCandidates; ++j) {
                        const int e = indices.at<int>(q, j);
                        if (e < 0) continue;
                        const Index::At at = index.at[size_t(e)];
                        const cv::Mat& indexed = index.labs[at.image];
                        const int x = at.x - d.x, y = at.y - d.y;
                        if (x < 0 || y < 0 || x > indexed.cols - kEnergyPatch ||
                            y > indexed.rows - kEnergyPatch)
                            continue;
                        best = std::min(best, patch_distance(indexed, x, y, sample));
                    }
                }
                if (best < 1e300)
                    sums[c] += std::sqrt(best / (kEnergyPatch * kEnergyPatch));
                else  // no candidate at all (never seen): the search's own, reduced distance
                    sums[c] += std::sqrt(dists.at<float>(int(i) * shifts, 0) /
                                         (kEnergyPatch * kEnergyPatch));
            }
        }
    });
    double total = 0;
    for (double s : sums)
        total += s;
    return total / double(samples);
}

}  // namespace tilejet::quality
