// libFuzzer: the texture map loader. Whatever it accepts must also render safely, because the
// sampler trusts a loaded map's patch bounds.
#include <cstdint>
#include <span>

#include "tilejet/synth/map_file.hpp"
#include "tilejet/synth/sampler.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace tilejet::synth;
    try {
        const TextureMap map = decode_texture_map(std::span(data, size), "fuzz.tjmap");
        const cv::Mat out = render_region(map, 7, Region{-40, 25, 48, 32}, 1);
        Sampler sampler(map, 7);
        for (int i = 0; i < 16; ++i)
            sampler.sample(i * 37 - 300, i * 53 - 200);
        (void)out;
    } catch (const SynthError&) {
    }
    return 0;
}
