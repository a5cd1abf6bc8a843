#include "tilejet/colour/colour_settings.hpp"

namespace tilejet::colour {

std::optional<Intent> parse_intent(std::string_view name) {
    if (name == "perceptual") return Intent::Perceptual;
    if (name == "relative") return Intent::RelativeColorimetric;
    if (name == "saturation") return Intent::Saturation;
    if (name == "absolute") return Intent::AbsoluteColorimetric;
    return std::nullopt;
}

std::string_view intent_name(Intent intent) {
    switch (intent) {
        case Intent::Perceptual:
            return "perceptual";
        case Intent::RelativeColorimetric:
            return "relative";
        case Intent::Saturation:
            return "saturation";
        case Intent::AbsoluteColorimetric:
            return "absolute";
    }
    return "perceptual";
}

}  // namespace tilejet::colour
