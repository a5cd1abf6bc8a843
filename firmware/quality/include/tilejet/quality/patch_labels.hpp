#pragma once

// Which piece of the texture map each pixel of a region shows: the cell image, or one shown
// patch. Where two neighbouring pixels carry different labels, a patch's graph-cut seam runs
// between them; the quality report measures what those seams look like.

#include <cstdint>
#include <opencv2/core/mat.hpp>

#include "tilejet/synth/sampler.hpp"
#include "tilejet/synth/texture_map.hpp"

namespace tilejet::quality {

// CV_32S of the region's size: 0 where the cell image shows, else an id > 0 that is the same
// for every pixel of one shown patch (one patch of one cell) and differs between any two shown
// patches in the region. Covers exactly the pixels render_region copies from the source.
cv::Mat render_patch_labels(const synth::TextureMap& map, uint64_t seed,
                            const synth::Region& region);

}  // namespace tilejet::quality
