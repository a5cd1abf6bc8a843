#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "lcms_context.hpp"

namespace tilejet::colour::detail {

// An ICC profile read from a file and checked before LittleCMS sees it: big enough for a header,
// the 'acsp' signature, the header's size not beyond the file, and the colour space asked for.
struct IccProfile {
    std::vector<uint8_t> bytes;
    Profile handle;
};

// The data colour space an ICC header declares, read as a plain number (a crafted file can hold
// a value outside LittleCMS's enum, found by fuzzing); 0 when there is no header to read it from.
uint32_t icc_data_space(const std::vector<uint8_t>& bytes);

// `role` names the profile in messages ("output profile", "source profile", ...).
// `space` is the data colour space the role needs (cmsSigCmykData, cmsSigRgbData, ...).
IccProfile load_icc_profile(LcmsContext& lcms, const std::filesystem::path& path, const char* role,
                            cmsColorSpaceSignature space);
// The same checks on bytes already read; `path` only names them in messages.
IccProfile parse_icc_profile(LcmsContext& lcms, std::vector<uint8_t> bytes,
                             const std::filesystem::path& path, const char* role,
                             cmsColorSpaceSignature space);

}  // namespace tilejet::colour::detail
