#include "tilejet/api/job_request.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>
#include <set>

#include "tilejet/synth/tile_region.hpp"

namespace tilejet::api {

namespace {

using nlohmann::json;

[[noreturn]] void bad(const std::string& field, const std::string& message) {
    throw ApiError(400, field, field + ": " + message);
}

std::int64_t integer(const json& j, const std::string& field, std::int64_t min, std::int64_t max) {
    if (!j.is_number_integer()) bad(field, "expected an integer");
    if (j.is_number_unsigned() && j.get<std::uint64_t>() > std::uint64_t(max))
        bad(field, "must be at most " + std::to_string(max));
    const auto v = j.get<std::int64_t>();
    if (v < min || v > max)
        bad(field, "must be " + std::to_string(min) + ".." + std::to_string(max));
    return v;
}

// Jobs name a design (or profile) in the daemon's own folder, never a path: a client must not
// make the daemon open /dev/zero or a FIFO, or learn which files exist. The same names as
// uploads take (PUT /api/designs/NAME): no slashes, no leading dot.
std::string file_name(const json& j, const std::string& field, const char* folder) {
    const std::string hint = std::string("the name of a file in the daemon's ") + folder +
                             " folder (GET /api/" + folder + ")";
    if (!j.is_string()) bad(field, "expected " + hint);
    const auto s = j.get<std::string>();
    const auto allowed = [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-';
    };
    if (s.empty() || s.size() > 100 || !std::isalnum(static_cast<unsigned char>(s.front())) ||
        !std::all_of(s.begin(), s.end(), allowed))
        bad(field, "expected " + hint + ", not a path");
    return s;
}

double millimetres(std::string_view text, const std::string& field) {
    double v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v))
        bad(field, "'" + std::string(text) + "' is not a number of millimetres");
    if (v < 1 || v > 5000) bad(field, "tile sides must be 1..5000 mm");
    return v;
}

}  // namespace

std::pair<double, double> parse_tile_mm(std::string_view text, const std::string& field) {
    const auto x = text.find('x');
    if (x == std::string_view::npos) bad(field, "expected WxH in mm, e.g. 300x300");
    return {millimetres(text.substr(0, x), field), millimetres(text.substr(x + 1), field)};
}

jobs::JobSpec parse_job_request(std::string_view body, int default_dpi) {
    if (body.size() > kMaxBodyBytes) throw ApiError(400, "body", "body: too large");
    json j;
    try {
        j = json::parse(body);
    } catch (const json::exception& e) {
        // Not only parse_error: a number too large for a double is out_of_range (fuzzing).
        bad("body", std::string("malformed JSON: ") + e.what());
    }
    if (!j.is_object()) bad("body", "expected a JSON object");
    static const std::set<std::string> known{"map", "seed",    "tiles",  "tile_mm",
                                             "dpi", "profile", "layout", "wall_width"};
    for (const auto& [key, value] : j.items())
        if (!known.contains(key)) bad(key, "unknown field");
    for (const char* required : {"map", "seed", "tiles", "tile_mm"})
        if (!j.contains(required)) bad(required, "missing (required)");

    jobs::JobSpec spec;
    spec.map = file_name(j["map"], "map", "designs");
    if (!j["seed"].is_number_integer() ||
        (!j["seed"].is_number_unsigned() && j["seed"].get<std::int64_t>() < 0))
        bad("seed", "expected an integer 0..2^64-1");
    spec.seed = j["seed"].get<std::uint64_t>();
    spec.tiles = integer(j["tiles"], "tiles", 1, 10'000'000);
    const json& mm = j["tile_mm"];
    if (mm.is_string()) {
        std::tie(spec.tile_width_mm, spec.tile_height_mm) =
            parse_tile_mm(mm.get<std::string>(), "tile_mm");
    } else if (mm.is_array() && mm.size() == 2 && mm[0].is_number() && mm[1].is_number()) {
        spec.tile_width_mm = millimetres(std::to_string(mm[0].get<double>()), "tile_mm");
        spec.tile_height_mm = millimetres(std::to_string(mm[1].get<double>()), "tile_mm");
    } else {
        bad("tile_mm", "expected \"WxH\" or [W, H] in mm");
    }
    spec.dpi = j.contains("dpi") ? int(integer(j["dpi"], "dpi", 10, 2400)) : default_dpi;
    if (j.contains("profile")) spec.profile = file_name(j["profile"], "profile", "profiles");
    if (j.contains("layout")) {
        if (!j["layout"].is_string())
            bad("layout", "expected a string: " + synth::tile_layout_choices());
        spec.layout = j["layout"].get<std::string>();
        if (!synth::parse_tile_layout(spec.layout))
            bad("layout", "'" + spec.layout + "' is not " + synth::tile_layout_choices());
    }
    if (j.contains("wall_width"))
        spec.wall_width = int(integer(j["wall_width"], "wall_width", 1, 100000));
    if (spec.dpi > 0) check_tile_fits(spec);
    return spec;
}

void check_tile_fits(const jobs::JobSpec& spec) {
    const double px = spec.tile_width_mm / 25.4 * spec.dpi * spec.tile_height_mm / 25.4 * spec.dpi;
    if (px * 4 > double(1u << 30))
        bad("dpi", "a tile of this size and dpi exceeds 1 GiB of separations");
}

}  // namespace tilejet::api
