#pragma once

// TileRenderer: a job's tiles as the heads' separations (its JobSetup), and sRGB proofs of the
// first few for the operator.
#include <filesystem>

#include "job_setup.hpp"
#include "separations.hpp"

namespace tilejet::daemon {

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

    std::int64_t job() const { return setup_.job; }
    const synth::TileGeometry& geometry() const { return setup_.geometry; }
    std::filesystem::path preview_path(std::int64_t index) const;

  private:
    void clear_stale_previews(const jobs::Job& job, const std::string& map_id) const;

    JobSetup setup_;
    std::filesystem::path previews_;
    int preview_tiles_ = 0;
};

}  // namespace tilejet::daemon
