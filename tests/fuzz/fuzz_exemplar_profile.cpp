// libFuzzer: the embedded-ICC reader for exemplar PNG (iCCP) and JPEG (APP2) files.
#include <cstdint>
#include <vector>

#include "embedded_profile.hpp"
#include "tilejet/synth/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    try {
        tilejet::synth::detail::parse_embedded_profile(std::vector<uint8_t>(data, data + size),
                                                       "fuzz.png");
    } catch (const tilejet::synth::SynthError&) {
    }
    return 0;
}
