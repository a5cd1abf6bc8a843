#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace tilejet::synth::detail {

// The ICC profile embedded in a PNG (iCCP chunk), JPEG (APP2 ICC_PROFILE segments) or TIFF
// (ICC profile tag) file; empty when there is none. OpenCV decodes pixels but drops profiles.
// Throws SynthError naming the file when the embedding itself is damaged.
std::vector<uint8_t> read_embedded_profile(const std::filesystem::path& path);

}  // namespace tilejet::synth::detail
