#pragma once

// JobSetup: what rendering one job's tiles takes, made one way for the heads' separations
// (TileRenderer) and the panel's pictures (TilePreviews): the tile geometry from millimetres
// and dpi, the job's colour transform, and its texture map converted once to that transform's
// CMYK (convert once, copy many: docs/design.md section 4).
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include "tilejet/colour/cmyk_transform.hpp"
#include "tilejet/jobs/job.hpp"
#include "tilejet/synth/texture_map.hpp"
#include "tilejet/synth/tile_region.hpp"

namespace tilejet::daemon {

// Tile size in pixels from millimetres at `dpi` (rounded to the nearest pixel).
int tile_pixels(double mm, int dpi);

// The job's colour pipeline: [colour] with the job's profile when it names one.
colour::ColourSettings job_colour(const jobs::JobSpec& spec, colour::ColourSettings base);

struct JobSetup {
    std::int64_t job = 0;
    std::uint64_t seed = 0;
    synth::TileGeometry geometry;
    std::string map_id;  // the design's, as loaded: the one the job was submitted with
    std::unique_ptr<colour::CmykTransform> transform;
    std::shared_ptr<const synth::TextureMap> cmyk_map;
};

// A job's design or profile file is missing, damaged, or no longer the map the job was
// submitted with (its tiles would be other tiles under the same indices); the message names it.
struct JobSetupError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Loads the job's design and builds its transform; throws JobSetupError.
JobSetup set_up_job(const jobs::Job& job, const colour::ColourSettings& colour);

}  // namespace tilejet::daemon
