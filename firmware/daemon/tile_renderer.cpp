#include "tile_renderer.hpp"

#include <sys/mman.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "tilejet/synth/sampler.hpp"

namespace tilejet::daemon {

namespace {

constexpr int kPreviewSide = 2048;  // px: the previews written for a job's first tiles

// A fresh tile buffer is 289 MB at 600 mm and 360 dpi: faulted in 4 KB pages that is 70 000 page
// faults, and rendering into fresh memory took 8 times as long as into a recycled buffer. Huge
// pages (where the kernel has them: transparent huge pages in "madvise" or "always" mode) make
// it 140. Only the first tiles of a job get fresh buffers; render-ahead recycles them after.
void reserve_tile_bytes(std::vector<std::uint8_t>& bytes, std::size_t size) {
    if (bytes.capacity() >= size) return;
    bytes = {};
    bytes.reserve(size);
    constexpr std::uintptr_t kHuge = 2 << 20;
    const auto begin = (reinterpret_cast<std::uintptr_t>(bytes.data()) + kHuge - 1) & ~(kHuge - 1);
    const auto end = (reinterpret_cast<std::uintptr_t>(bytes.data()) + size) & ~(kHuge - 1);
    if (end > begin)
        ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);  // a hint only
}

}  // namespace

TileRenderer::TileRenderer(const jobs::Job& job, const colour::ColourSettings& colour,
                           std::filesystem::path previews, int preview_tiles)
    : setup_(set_up_job(job, colour)),
      previews_(std::move(previews)),
      preview_tiles_(preview_tiles) {
    if (!previews_.empty() && preview_tiles_ > 0) clear_stale_previews(job, setup_.map_id);
}

Separations TileRenderer::render(std::int64_t index, int threads,
                                 std::vector<std::uint8_t> buffer) const {
    const synth::Region region =
        synth::tile_region(setup_.seed, std::uint64_t(index), setup_.geometry);
    Separations s{setup_.job, index, region.width, region.height, std::move(buffer)};
    const size_t size = size_t(region.width) * size_t(region.height) * 4;
    reserve_tile_bytes(s.bytes, size);
    s.bytes.resize(size);
    synth::render_region(*setup_.cmyk_map, setup_.seed, region, s.bytes.data(),
                         size_t(region.width) * 4, threads);
    if (index < preview_tiles_ && !previews_.empty() &&
        !std::filesystem::exists(preview_path(index)))
        write_preview(s, preview_path(index));
    return s;
}

void TileRenderer::clear_stale_previews(const jobs::Job& job, const std::string& map_id) const {
    // Previews are kept per job number, and a new job store (the demo's, a line's after a
    // reinstall) numbers its jobs from 1 again: proofs left by another job of that number,
    // of another design, would be shown as this one's. A stamp says whose they are.
    namespace fs = std::filesystem;
    const fs::path dir = previews_ / ("job-" + std::to_string(setup_.job));
    const std::string stamp = "created " + job.created + ", map " + map_id + ", seed " +
                              std::to_string(job.spec.seed) + "\n";
    std::error_code ec;
    std::string found;
    if (std::ifstream in(dir / "job.txt"); in) found.assign(std::istreambuf_iterator<char>(in), {});
    if (found == stamp) return;
    fs::remove_all(dir, ec);
    fs::create_directories(dir, ec);
    std::ofstream(dir / "job.txt") << stamp;
}

std::filesystem::path TileRenderer::preview_path(std::int64_t index) const {
    return previews_ / ("job-" + std::to_string(setup_.job)) /
           ("tile-" + std::to_string(index) + ".png");
}

void TileRenderer::write_preview(const Separations& tile, const std::filesystem::path& png) const {
    const cv::Mat cmyk(tile.height, tile.width, CV_8UC4,
                       const_cast<std::uint8_t*>(tile.bytes.data()));
    // A proof to look at, not to print from: at most kPreviewSide px across. A 600 mm tile at
    // 360 dpi in full was an 82 MB PNG, seconds of a render thread's time each. The inks are
    // averaged before the proof (area averaging), which a proof this size cannot tell.
    const double scale = std::min(1.0, double(kPreviewSide) / std::max(tile.width, tile.height));
    cv::Mat small = cmyk;
    if (scale < 1)
        cv::resize(cmyk, small,
                   {std::max(1, int(tile.width * scale)), std::max(1, int(tile.height * scale))}, 0,
                   0, cv::INTER_AREA);
    cv::Mat bgr;
    cv::cvtColor(setup_.transform->proof(small), bgr, cv::COLOR_RGB2BGR);
    std::filesystem::create_directories(png.parent_path());
    cv::imwrite(png.string(), bgr);
}

}  // namespace tilejet::daemon
