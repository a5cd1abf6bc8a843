#include "tilejet/colour/cmyk_map.hpp"

namespace tilejet::colour {

std::shared_ptr<const synth::TextureMap> convert_map(const synth::TextureMap& map,
                                                     const CmykTransform& transform) {
    auto converted = std::make_shared<synth::TextureMap>(map);  // id kept: same plane, other inks
    converted->source = transform.to_cmyk(map.source);
    for (synth::CellImage& image : converted->cell_images)
        image.rgb = transform.to_cmyk(image.rgb);
    return converted;
}

std::shared_ptr<const synth::TextureMap> CmykMapCache::get(const synth::TextureMap& map,
                                                           const CmykTransform& transform) {
    const std::string key = map.id_hex() + "/" + transform.key();
    {
        std::lock_guard lock(mutex_);
        if (auto it = maps_.find(key); it != maps_.end()) return it->second;
    }
    // Converted outside the lock: two threads may both convert once; both results are equal.
    auto converted = convert_map(map, transform);
    std::lock_guard lock(mutex_);
    return maps_.emplace(key, std::move(converted)).first->second;
}

size_t CmykMapCache::size() const {
    std::lock_guard lock(mutex_);
    return maps_.size();
}

}  // namespace tilejet::colour
