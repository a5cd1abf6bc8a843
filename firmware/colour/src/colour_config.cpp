#include "tilejet/colour/colour_config.hpp"

#include <filesystem>

#include "tilejet/config/paths.hpp"
#include "tilejet/config/section.hpp"

namespace tilejet::colour {

ColourSettings parse_colour_section(const toml::table* table, const config::ConfigSource& source) {
    config::ConfigSection s(table, source, kColourSection);
    ColourSettings c;
    c.output_profile = config::resolve_path(source, s.require_string("output_profile"));
    c.source_profile = config::resolve_path(source, s.get_string("source_profile", ""));
    const std::string intent = s.get_choice("intent", "perceptual", intent_names());
    c.intent = *parse_intent(intent);
    c.black_point_compensation = s.get_bool("black_point_compensation", false);
    c.ink_limit_percent = s.get_double("ink_limit_percent", 300, 0, 400);
    c.ink_curves = config::resolve_path(source, s.get_string("ink_curves", ""));
    if (!std::filesystem::exists(c.output_profile))
        s.fail("output_profile", "no such file '" + c.output_profile.string() + "'");
    s.finish();
    return c;
}

}  // namespace tilejet::colour
