#include "job_setup.hpp"

#include <cmath>

#include "tilejet/colour/cmyk_map.hpp"
#include "tilejet/synth/map_file.hpp"

namespace tilejet::daemon {

int tile_pixels(double mm, int dpi) {
    return int(std::lround(mm / 25.4 * dpi));
}

colour::ColourSettings job_colour(const jobs::JobSpec& spec, colour::ColourSettings base) {
    if (!spec.profile.empty()) base.output_profile = spec.profile;
    return base;
}

JobSetup set_up_job(const jobs::Job& job, const colour::ColourSettings& colour) {
    JobSetup s;
    s.job = job.id;
    s.seed = job.spec.seed;
    s.geometry = {tile_pixels(job.spec.tile_width_mm, job.spec.dpi),
                  tile_pixels(job.spec.tile_height_mm, job.spec.dpi),
                  synth::parse_tile_layout(job.spec.layout).value_or(synth::TileLayout::Scatter),
                  job.spec.wall_width};
    synth::TextureMap map;
    try {
        map = synth::load_texture_map(job.spec.map);
        s.transform = std::make_unique<colour::CmykTransform>(job_colour(job.spec, colour));
    } catch (const std::exception& e) {  // the map or profile file, named in the message
        throw JobSetupError(e.what());
    }
    s.map_id = map.id_hex();
    if (!job.spec.map_id.empty() && s.map_id != job.spec.map_id)
        throw JobSetupError(job.name() + ": design file " + job.spec.map + " is now map " +
                            s.map_id + ", the job was submitted with map " + job.spec.map_id +
                            ": refusing to print other tiles under the same indices");
    s.cmyk_map = colour::convert_map(map, *s.transform);
    return s;
}

}  // namespace tilejet::daemon
