#include "tilejet/colour/cmyk_map.hpp"

namespace tilejet::colour {

std::shared_ptr<const synth::TextureMap> convert_map(const synth::TextureMap& map,
                                                     const CmykTransform& transform) {
    auto converted = std::make_shared<synth::TextureMap>(map);  // id kept: same plane, other inks
    converted->source = transform.to_cmyk(map.source);
    for (synth::CellImage& image : converted->cell_images)
        image.pixels = transform.to_cmyk(image.pixels);
    return converted;
}

}  // namespace tilejet::colour
