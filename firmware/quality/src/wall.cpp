#include "tilejet/quality/wall.hpp"

#include <cmath>

#include "tilejet/quality/patch_labels.hpp"
#include "tilejet/synth/error.hpp"
#include "tilejet/synth/internal/diamond.hpp"
#include "tilejet/synth/internal/mix64.hpp"
#include "tilejet/synth/internal/parallel_for.hpp"
#include "tilejet/synth/quilt.hpp"
#include "tilejet/synth/sampler.hpp"
#include "tilejet/synth/tile_region.hpp"

namespace tilejet::quality {

namespace {

WallSpec checked(WallSpec spec) {
    if (spec.tiles < 1) throw synth::SynthError("a wall needs at least one tile");
    if (spec.tile.width < 1 || spec.tile.height < 1)
        throw synth::SynthError("tile size " + std::to_string(spec.tile.width) + "x" +
                                std::to_string(spec.tile.height) + " is empty");
    if (spec.columns <= 0) spec.columns = int(std::ceil(std::sqrt(double(spec.tiles))));
    return spec;
}

Wall empty_wall(const WallSpec& spec) {
    Wall wall;
    wall.tile = spec.tile;
    wall.columns = spec.columns;
    wall.tiles.resize(size_t(spec.tiles));
    wall.seams.resize(size_t(spec.tiles));
    return wall;
}

// A seam between a crop's last column (row) and the pixel beyond it lies outside the crop.
void drop_outer_seams(cv::Mat& seams) {
    for (int y = 0; y < seams.rows; ++y)
        seams.at<uint8_t>(y, seams.cols - 1) &= uint8_t(~kSeamRight);
    for (int x = 0; x < seams.cols; ++x)
        seams.at<uint8_t>(seams.rows - 1, x) &= uint8_t(~kSeamBelow);
}

synth::Region region_of(const WallSpec& spec, int k) {
    return synth::tile_region(
        spec.seed, uint64_t(k),
        {spec.tile.width, spec.tile.height, synth::TileLayout::Wall, spec.columns});
}

}  // namespace

cv::Mat Wall::laid(cv::Rect area) const {
    cv::Mat out(area.size(), CV_8UC3, cv::Scalar::all(128));
    for (size_t k = 0; k < tiles.size(); ++k) {
        const cv::Rect at(int(k % size_t(columns)) * tile.width,
                          int(k / size_t(columns)) * tile.height, tile.width, tile.height);
        const cv::Rect both = at & area;
        if (both.empty()) continue;
        tiles[k](both - at.tl()).copyTo(out(both - area.tl()));
    }
    return out;
}

Wall tilejet_wall(const synth::TextureMap& map, const WallSpec& raw) {
    const WallSpec spec = checked(raw);
    Wall wall = empty_wall(spec);
    // Tiles in parallel, each rendered on one thread: same bytes as any other split.
    synth::detail::parallel_for(size_t(spec.tiles), spec.threads, [&](size_t k) {
        const synth::Region region = region_of(spec, int(k));
        wall.tiles[k] = synth::render_region(map, spec.seed, region, 1);
        wall.seams[k] = seams_from_labels(render_patch_labels(map, spec.seed, region));
    });
    return wall;
}

Wall cell_wall(const synth::TextureMap& map, const WallSpec& raw) {
    const WallSpec spec = checked(raw);
    Wall wall = empty_wall(spec);
    const cv::Mat& cell = map.cell_images.front().pixels;
    for (int k = 0; k < spec.tiles; ++k) {
        const synth::Region region = region_of(spec, k);
        cv::Mat tile(spec.tile, CV_8UC3);
        for (int y = 0; y < tile.rows; ++y) {
            const cv::Vec3b* row =
                cell.ptr<cv::Vec3b>(int(synth::detail::floor_mod(region.y + y, map.cell_height)));
            cv::Vec3b* dst = tile.ptr<cv::Vec3b>(y);
            int64_t u = synth::detail::floor_mod(region.x, map.cell_width);
            for (int x = 0; x < tile.cols; ++x, u = u + 1 == map.cell_width ? 0 : u + 1)
                dst[x] = row[u];
        }
        wall.tiles[size_t(k)] = tile;
        wall.seams[size_t(k)] = cv::Mat();  // the cell image's own quilting seams are unknown
    }
    return wall;
}

Wall canvas_wall(const cv::Mat& exemplar, const WallSpec& raw, cv::Size canvas_size, int block) {
    const WallSpec spec = checked(raw);
    canvas_size.width = std::max(canvas_size.width, spec.tile.width);
    canvas_size.height = std::max(canvas_size.height, spec.tile.height);
    const synth::QuiltedImage canvas = synth::quilt_texture(
        exemplar, canvas_size, synth::detail::hash_combine(spec.seed, 0xca4a5ull), block);
    const cv::Mat seams = seams_from_provenance(canvas.provenance, exemplar.cols);
    Wall wall = empty_wall(spec);
    synth::detail::Rng rng(synth::detail::hash_combine(spec.seed, 0xc40bull));
    for (int k = 0; k < spec.tiles; ++k) {
        const cv::Rect crop(rng.range(0, canvas_size.width - spec.tile.width),
                            rng.range(0, canvas_size.height - spec.tile.height), spec.tile.width,
                            spec.tile.height);
        wall.tiles[size_t(k)] = canvas.rgb(crop).clone();
        cv::Mat s = seams(crop).clone();
        drop_outer_seams(s);
        wall.seams[size_t(k)] = s;
    }
    return wall;
}

Wall quilt_wall(const cv::Mat& exemplar, const WallSpec& raw, int block) {
    const WallSpec spec = checked(raw);
    Wall wall = empty_wall(spec);
    synth::detail::parallel_for(size_t(spec.tiles), spec.threads, [&](size_t k) {
        const synth::QuiltedImage q = synth::quilt_texture(
            exemplar, spec.tile, synth::detail::hash_combine(spec.seed ^ 0x9017ull, k), block);
        wall.tiles[k] = q.rgb;
        cv::Mat s = seams_from_provenance(q.provenance, exemplar.cols);
        drop_outer_seams(s);
        wall.seams[k] = s;
    });
    return wall;
}

cv::Mat seams_from_provenance(const cv::Mat& provenance, int exemplar_width) {
    const int w = provenance.cols, h = provenance.rows;
    cv::Mat seams(provenance.size(), CV_8U, cv::Scalar(0));
    for (int y = 0; y < h; ++y) {
        const int32_t* p = provenance.ptr<int32_t>(y);
        const int32_t* below = provenance.ptr<int32_t>((y + 1) % h);
        uint8_t* s = seams.ptr<uint8_t>(y);
        for (int x = 0; x < w; ++x) {
            const int32_t right = p[(x + 1) % w];
            const bool right_continues =
                right == p[x] + 1 && (p[x] % exemplar_width) != exemplar_width - 1;
            const bool below_continues = below[x] == p[x] + exemplar_width;
            s[x] = uint8_t((right_continues ? 0 : kSeamRight) | (below_continues ? 0 : kSeamBelow));
        }
    }
    return seams;
}

cv::Mat seams_from_labels(const cv::Mat& labels) {
    const int w = labels.cols, h = labels.rows;
    cv::Mat seams(labels.size(), CV_8U, cv::Scalar(0));
    for (int y = 0; y < h; ++y) {
        const int32_t* l = labels.ptr<int32_t>(y);
        const int32_t* below = y + 1 < h ? labels.ptr<int32_t>(y + 1) : nullptr;
        uint8_t* s = seams.ptr<uint8_t>(y);
        for (int x = 0; x < w; ++x)
            s[x] = uint8_t((x + 1 < w && l[x + 1] != l[x] ? kSeamRight : 0) |
                           (below && below[x] != l[x] ? kSeamBelow : 0));
    }
    return seams;
}

}  // namespace tilejet::quality
