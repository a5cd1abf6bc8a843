#include "tile_previews.hpp"

#include <cmath>
#include <functional>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "job_setup.hpp"
#include "tilejet/colour/cmyk_transform.hpp"
#include "tilejet/synth/sampler.hpp"
#include "tilejet/synth/tile_region.hpp"

namespace tilejet::daemon {

namespace {
constexpr size_t kPreparedJobs = 2;  // the job printing and the one looked at
constexpr size_t kCachedPngs = 256;  // ~10 KB each
constexpr int kSupersample = 2;      // samples per thumbnail pixel per axis: no aliased grain
constexpr int kGrout = 2;            // pixels between tiles on the wall preview
}  // namespace

TilePreviews::TilePreviews(colour::ColourSettings colour) : colour_(std::move(colour)) {}
TilePreviews::~TilePreviews() = default;

std::shared_ptr<const JobSetup> TilePreviews::prepare(const jobs::Job& job) {
    {
        std::lock_guard lock(mutex_);
        for (auto it = prepared_.begin(); it != prepared_.end(); ++it)
            if ((*it)->job == job.id) {
                prepared_.splice(prepared_.begin(), prepared_, it);
                return prepared_.front();
            }
    }
    auto p = std::make_shared<const JobSetup>(set_up_job(job, colour_));
    std::lock_guard lock(mutex_);
    prepared_.push_front(p);
    if (prepared_.size() > kPreparedJobs) prepared_.pop_back();
    return p;
}

std::string TilePreviews::cached(const Key& key, const std::function<std::string()>& make) {
    {
        std::lock_guard lock(mutex_);
        for (auto it = pngs_.begin(); it != pngs_.end(); ++it)
            if (it->first == key) {
                pngs_.splice(pngs_.begin(), pngs_, it);
                return pngs_.front().second;
            }
    }
    std::string png = make();
    std::lock_guard lock(mutex_);
    pngs_.emplace_front(key, png);
    if (pngs_.size() > kCachedPngs) pngs_.pop_back();
    return png;
}

namespace {

// The tile's region sampled on a regular grid, supersampled and averaged down, in sRGB (BGR
// order for OpenCV).
cv::Mat proof_thumbnail(const synth::TextureMap& cmyk_map, std::uint64_t seed,
                        const synth::Region& region, const colour::CmykTransform& transform,
                        cv::Size size) {
    const cv::Size fine(size.width * kSupersample, size.height * kSupersample);
    cv::Mat cmyk(fine, CV_8UC4);
    synth::Sampler sampler(cmyk_map, seed);
    for (int r = 0; r < fine.height; ++r) {
        const std::int64_t y = region.y + std::int64_t((r + 0.5) * region.height / fine.height);
        auto* row = cmyk.ptr<std::uint8_t>(r);
        for (int c = 0; c < fine.width; ++c) {
            const std::int64_t x = region.x + std::int64_t((c + 0.5) * region.width / fine.width);
            const std::uint8_t* px = sampler.pixel(x, y);
            std::copy(px, px + 4, row + 4 * c);
        }
    }
    cv::Mat rgb, small, bgr;
    rgb = transform.proof(cmyk);
    cv::resize(rgb, small, size, 0, 0, cv::INTER_AREA);
    cv::cvtColor(small, bgr, cv::COLOR_RGB2BGR);
    return bgr;
}

cv::Size fit(int width, int height, int max_side) {
    const double scale = double(max_side) / std::max(width, height);
    return {std::max(1, int(std::lround(width * std::min(1.0, scale)))),
            std::max(1, int(std::lround(height * std::min(1.0, scale))))};
}

std::string encode(const cv::Mat& bgr) {
    std::vector<std::uint8_t> bytes;
    cv::imencode(".png", bgr, bytes);
    return {bytes.begin(), bytes.end()};
}

}  // namespace

std::string TilePreviews::tile_png(const jobs::Job& job, std::int64_t index, int max_side) {
    return cached({job.id, index, max_side}, [&] {
        std::lock_guard lock(render_mutex_);
        const auto p = prepare(job);
        const auto region = synth::tile_region(p->seed, std::uint64_t(index), p->geometry);
        return encode(proof_thumbnail(*p->cmyk_map, p->seed, region, *p->transform,
                                      fit(region.width, region.height, max_side)));
    });
}

std::string TilePreviews::wall_png(const jobs::Job& job, const std::vector<std::int64_t>& indices,
                                   int max_side) {
    std::lock_guard lock(render_mutex_);
    const auto p = prepare(job);
    const int n = int(indices.size());
    const int columns =
        std::max(1, p->geometry.layout == synth::TileLayout::Wall
                        ? std::min(n, p->geometry.wall_width)
                        : int(std::ceil(std::sqrt(double(std::max(n, 1)) * p->geometry.height /
                                                  std::max(1, p->geometry.width)))));
    const int rows = std::max(1, (n + columns - 1) / columns);
    const int cell =
        std::max(8, (max_side - kGrout * (std::max(columns, rows) - 1)) / std::max(columns, rows));
    const cv::Size tile = fit(p->geometry.width, p->geometry.height, cell);
    cv::Mat wall(rows * tile.height + (rows - 1) * kGrout,
                 columns * tile.width + (columns - 1) * kGrout, CV_8UC3, cv::Scalar(70, 70, 70));
    for (int i = 0; i < n; ++i) {
        const auto region =
            synth::tile_region(p->seed, std::uint64_t(indices[size_t(i)]), p->geometry);
        const cv::Mat thumb = proof_thumbnail(*p->cmyk_map, p->seed, region, *p->transform, tile);
        thumb.copyTo(
            wall(cv::Rect((i % columns) * (tile.width + kGrout),
                          (i / columns) * (tile.height + kGrout), tile.width, tile.height)));
    }
    return encode(wall);
}

}  // namespace tilejet::daemon
