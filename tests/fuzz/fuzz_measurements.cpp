// libFuzzer: CGATS measurement files (.ti3) for profiling.
#include <cstdint>
#include <span>

#include "tilejet/colour/cmyk_transform.hpp"
#include "tilejet/colour/measurements.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    try {
        tilejet::colour::parse_measurements(std::span(data, size), "fuzz.ti3");
    } catch (const tilejet::colour::ColourError&) {
    }
    return 0;
}
