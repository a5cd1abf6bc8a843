#pragma once

// TileRenderer: everything one job needs to render its tiles: the texture map converted once
// to the job's CMYK pipeline, and the tile geometry from millimetres and dpi.
#include <filesystem>
#include <memory>

#include "separations.hpp"
#include "tilejet/colour/cmyk_transform.hpp"
#include "tilejet/jobs/job.hpp"
#include "tilejet/synth/texture_map.hpp"
#include "tilejet/synth/tile_region.hpp"

namespace tilejet::daemon {

// Tile size in pixels from millimetres at `dpi` (rounded to the nearest pixel).
int tile_pixels(double mm, int dpi);

// The job's colour pipeline: [colour] with the job's profile when it names one.
colour::ColourSettings job_colour(const jobs::JobSpec& spec, colour::ColourSettings base);

class TileRenderer {
  public:
    // Loads the map and builds the transform; throws naming the map or profile file.
    // Tiles below `preview_tiles` also get an sRGB proof in `previews`/job-N/tile-K.png.
    TileRenderer(const jobs::Job& job, const colour::ColourSettings& colour,
                 std::filesystem::path previews = {}, int preview_tiles = 0);

    // `buffer`: a tile's bytes that are no longer needed, reused so that a 300 MB tile costs
    // no fresh pages (the kernel zeroes every new page: more time than the render itself).
    Separations render(std::int64_t index, int threads = 1,
                       std::vector<std::uint8_t> buffer = {}) const;
    // An sRGB soft proof of a tile, for previews.
    void write_preview(const Separations& tile, const std::filesystem::path& png) const;

    std::int64_t job() const { return job_; }
    const synth::TileGeometry& geometry() const { return geometry_; }
    std::filesystem::path preview_path(std::int64_t index) const;

  private:
    void clear_stale_previews(const jobs::Job& job, const std::string& map_id) const;

    std::int64_t job_;
    std::filesystem::path previews_;
    int preview_tiles_ = 0;
    std::uint64_t seed_;
    synth::TileGeometry geometry_;
    std::unique_ptr<colour::CmykTransform> transform_;
    std::shared_ptr<const synth::TextureMap> cmyk_map_;
};

}  // namespace tilejet::daemon
