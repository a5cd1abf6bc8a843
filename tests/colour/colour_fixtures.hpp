#pragma once

#include <filesystem>

namespace tilejet::test {

// A CMYK output profile built at build time by ArgyllCMS colprof (low quality, quick) from
// Debian's FOGRA39L.ti3: a real offset-press characterization standing in for a line's.
inline std::filesystem::path test_cmyk_profile() {
    return TILEJET_TEST_CMYK_PROFILE;
}
inline std::filesystem::path fogra39_measurements() {
    return TILEJET_FOGRA39_TI3;
}

}  // namespace tilejet::test
