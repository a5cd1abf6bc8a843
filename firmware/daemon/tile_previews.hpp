#pragma once

// TilePreviews: the panel's pictures. Small sRGB soft proofs of a job's tiles, sampled with
// the same Sampler and CMYK map the heads' separations come from, then seen back through the
// job's profile. Rendered on the API's threads, one picture at a time (a panel can never take
// more than one core from render-ahead), and cached: a tile never changes.
#include <functional>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <tuple>
#include <vector>

#include "tilejet/colour/colour_settings.hpp"
#include "tilejet/jobs/job.hpp"

namespace tilejet::daemon {

struct JobSetup;  // job_setup.hpp

class TilePreviews {
  public:
    explicit TilePreviews(colour::ColourSettings colour);
    ~TilePreviews();

    // PNG of tile `index`, at most `max_side` pixels on its longer side.
    std::string tile_png(const jobs::Job& job, std::int64_t index, int max_side);
    // PNG of `indices` laid as a wall: the job's wall width for wall jobs, else a square-ish
    // grid, with a grout line between tiles.
    std::string wall_png(const jobs::Job& job, const std::vector<std::int64_t>& indices,
                         int max_side);

  private:
    std::shared_ptr<const JobSetup> prepare(const jobs::Job& job);
    std::string cached(const std::tuple<std::int64_t, std::int64_t, int>& key,
                       const std::function<std::string()>& make);

    colour::ColourSettings colour_;
    std::mutex render_mutex_;                                 // one picture at a time
    std::mutex mutex_;                                        // the caches
    std::list<std::shared_ptr<const JobSetup>> prepared_;     // most recent first, a few jobs
    using Key = std::tuple<std::int64_t, std::int64_t, int>;  // job, tile, size
    std::list<std::pair<Key, std::string>> pngs_;             // most recent first
};

}  // namespace tilejet::daemon
