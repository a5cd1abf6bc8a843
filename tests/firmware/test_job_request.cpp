// Request parsing of the daemon's API: broken input is a 400 naming the field, never a crash.
#include <catch2/catch.hpp>

#include "tilejet/api/job_request.hpp"

using tilejet::api::ApiError;
using tilejet::api::parse_job_request;

namespace {

// The field an error names, or "" when the body is accepted.
std::string rejected_field(const std::string& body) {
    try {
        parse_job_request(body, 360);
    } catch (const ApiError& e) {
        CHECK(e.status() == 400);
        CHECK(std::string(e.what()).find(e.field()) != std::string::npos);
        return e.field();
    }
    return "";
}

}  // namespace

TEST_CASE("a good job request parses, with the default dpi", "[api]") {
    const auto spec = parse_job_request(
        R"({"map":"m.tjmap","seed":18446744073709551615,"tiles":50,"tile_mm":"300x600","layout":"wall","wall_width":4})",
        360);
    CHECK(spec.map == "m.tjmap");
    CHECK(spec.seed == 18446744073709551615ull);
    CHECK(spec.tiles == 50);
    CHECK(spec.tile_width_mm == 300);
    CHECK(spec.tile_height_mm == 600);
    CHECK(spec.dpi == 360);
    CHECK(spec.layout == "wall");
    CHECK(spec.wall_width == 4);
    CHECK(parse_job_request(R"({"map":"m","seed":1,"tiles":1,"tile_mm":[100,200],"dpi":72})", 360)
              .tile_height_mm == 200);
}

TEST_CASE("broken job requests are rejected naming the field", "[api]") {
    CHECK(rejected_field("{\"map\": \"/m\", ") == "body");
    CHECK(rejected_field("") == "body");
    CHECK(rejected_field("[1,2]") == "body");
    CHECK(rejected_field("\xff\xfe") == "body");
    // Regression (fuzzing): a number too large for a double escaped as an uncaught exception.
    CHECK(rejected_field("999999999999E99999999999") == "body");
    CHECK(rejected_field(R"({"map":"m","seed":1e999999,"tiles":5,"tile_mm":"300x300"})") == "body");
    const std::string ok = R"("map":"m","seed":1,"tiles":5,"tile_mm":"300x300")";
    CHECK(rejected_field("{" + ok + R"(,"colour":"red"})") == "colour");
    CHECK(rejected_field(R"({"seed":1,"tiles":5,"tile_mm":"300x300"})") == "map");
    // Designs are named in the daemon's designs folder, never by a path.
    for (const char* map :
         {"/abs/m.tjmap", "sub/m.tjmap", "../m.tjmap", ".hidden", "", "/dev/zero"}) {
        INFO(map);
        CHECK(rejected_field(std::string(R"({"map":")") + map +
                             R"(","seed":1,"tiles":5,"tile_mm":"300x300"})") == "map");
    }
    CHECK(rejected_field(R"({"map":7,"seed":1,"tiles":5,"tile_mm":"300x300"})") == "map");
    CHECK(rejected_field(R"({"map":"m","seed":-1,"tiles":5,"tile_mm":"300x300"})") == "seed");
    CHECK(rejected_field(R"({"map":"m","seed":"7","tiles":5,"tile_mm":"300x300"})") == "seed");
    CHECK(rejected_field(R"({"map":"m","seed":1.5,"tiles":5,"tile_mm":"300x300"})") == "seed");
    CHECK(rejected_field(R"({"map":"m","seed":1,"tiles":0,"tile_mm":"300x300"})") == "tiles");
    CHECK(rejected_field(R"({"map":"m","seed":1,"tiles":99999999999,"tile_mm":"300x300"})") ==
          "tiles");
    CHECK(rejected_field(R"({"map":"m","seed":1,"tiles":5,"tile_mm":"300"})") == "tile_mm");
    CHECK(rejected_field(R"({"map":"m","seed":1,"tiles":5,"tile_mm":"0x300"})") == "tile_mm");
    CHECK(rejected_field(R"({"map":"m","seed":1,"tiles":5,"tile_mm":"nanx300"})") == "tile_mm");
    CHECK(rejected_field(R"({"map":"m","seed":1,"tiles":5,"tile_mm":[1]})") == "tile_mm");
    CHECK(rejected_field("{" + ok + R"(,"dpi":5})") == "dpi");
    CHECK(rejected_field("{" + ok + R"(,"dpi":2400})") == "dpi");  // 1 GiB of separations
    CHECK(rejected_field("{" + ok + R"(,"layout":"spiral"})") == "layout");
    CHECK(rejected_field("{" + ok + R"(,"wall_width":0})") == "wall_width");
    CHECK(rejected_field("{" + ok + R"(,"profile":"/etc/line.icc"})") == "profile");
}

TEST_CASE("an oversize body is refused before it is parsed", "[api]") {
    const std::string huge(tilejet::api::kMaxBodyBytes + 1, ' ');
    try {
        parse_job_request(huge, 360);
        FAIL("accepted");
    } catch (const ApiError& e) {
        CHECK(e.status() == 400);
        CHECK(e.field() == "body");
    }
}
