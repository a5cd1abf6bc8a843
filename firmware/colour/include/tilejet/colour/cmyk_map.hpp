#pragma once

// Convert once, copy many (docs/design.md section 4): rendering only copies pixels of the map's
// cell image and source, so converting those to CMYK once gives, byte for byte, what
// transforming every rendered pixel would, at copy speed. synth::render_region on a converted
// map renders C,M,Y,K directly.

#include <memory>

#include "tilejet/colour/cmyk_transform.hpp"
#include "tilejet/synth/texture_map.hpp"

namespace tilejet::colour {

std::shared_ptr<const synth::TextureMap> convert_map(const synth::TextureMap& map,
                                                     const CmykTransform& transform);

}  // namespace tilejet::colour
