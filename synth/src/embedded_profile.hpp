#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace tilejet::synth::detail {

// The ICC profile embedded in a PNG (iCCP chunk), JPEG (APP2 ICC_PROFILE segments) or TIFF
// (ICC profile tag) file; empty when there is none. OpenCV decodes pixels but drops profiles.
// Throws SynthError naming the file when the embedding itself is damaged.
std::vector<uint8_t> read_embedded_profile(const std::filesystem::path& path);
// PNG and JPEG from bytes already read (`path` names them in messages); TIFF needs the file.
std::vector<uint8_t> parse_embedded_profile(const std::vector<uint8_t>& file,
                                            const std::filesystem::path& path);

}  // namespace tilejet::synth::detail
