#include "tilejet/colour/colour_settings.hpp"

#include "tilejet/config/enum_names.hpp"

namespace tilejet::colour {

namespace {

constexpr config::EnumNames kIntents{std::array<std::pair<Intent, std::string_view>, 4>{{
    {Intent::Perceptual, "perceptual"},
    {Intent::RelativeColorimetric, "relative"},
    {Intent::Saturation, "saturation"},
    {Intent::AbsoluteColorimetric, "absolute"},
}}};

}  // namespace

std::optional<Intent> parse_intent(std::string_view name) {
    return kIntents.parse(name);
}

std::string_view intent_name(Intent intent) {
    return kIntents.name(intent);
}

std::vector<std::string> intent_names() {
    return kIntents.names();
}

}  // namespace tilejet::colour
