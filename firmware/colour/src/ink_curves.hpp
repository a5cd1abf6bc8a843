#pragma once

#include <filesystem>

#include "lcms_context.hpp"

namespace tilejet::colour::detail {

// Per-ink linearization from a small TOML table, as a CMYK -> CMYK device link:
//
//   # ink in -> ink out, percent; points ascending from 0 to 100
//   [cyan]
//   points = [[0, 0], [50, 44], [100, 100]]
//   [magenta]  [yellow]  [black]   (an ink left out keeps its values)
//
// Errors name the file, the section and the key.
Profile load_ink_curves(LcmsContext& lcms, const std::filesystem::path& path);

}  // namespace tilejet::colour::detail
