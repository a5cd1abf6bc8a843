#pragma once

// How a line turns RGB designs into ink (docs/design.md section 4). One ColourSettings names one
// colour pipeline; the config's [colour] section and the command line's --cmyk options fill it.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tilejet::colour {

enum class Intent { Perceptual, RelativeColorimetric, Saturation, AbsoluteColorimetric };

std::optional<Intent> parse_intent(
    std::string_view name);  // perceptual|relative|saturation|absolute
std::string_view intent_name(Intent intent);
std::vector<std::string> intent_names();  // every intent, for config choices and messages

struct ColourSettings {
    std::filesystem::path output_profile;  // the line's CMYK ICC profile (required)
    std::filesystem::path source_profile;  // RGB profile of the design; empty: sRGB
    Intent intent = Intent::Perceptual;
    bool black_point_compensation = false;
    double ink_limit_percent = 300;    // total area coverage, C+M+Y+K, in percent (0-400)
    std::filesystem::path ink_curves;  // per-ink linearization table (TOML); empty: none
};

}  // namespace tilejet::colour
