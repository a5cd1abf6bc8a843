#include <catch2/catch.hpp>

#include "../../firmware/daemon/line_state.hpp"
#include "tilejet/api/access.hpp"
#include "tilejet/colour/colour_settings.hpp"
#include "tilejet/jobs/job.hpp"
#include "tilejet/synth/synthesize.hpp"
#include "tilejet/synth/tile_region.hpp"

using namespace tilejet;

// The spellings config files, the API, the job store and the CLI use (README: config keys,
// API fields): each module's table must keep them, both ways.
TEST_CASE("every module spells its enums as config files, the API and the store do",
          "[enum_names]") {
    CHECK(api::role_names() == std::vector<std::string>{"viewer", "operator", "engineer"});
    CHECK(api::parse_role("operator") == api::Role::operator_);
    CHECK(api::to_string(api::Role::engineer) == "engineer");

    CHECK(colour::intent_names() ==
          std::vector<std::string>{"perceptual", "relative", "saturation", "absolute"});
    CHECK(colour::parse_intent("relative") == colour::Intent::RelativeColorimetric);
    CHECK(colour::intent_name(colour::Intent::AbsoluteColorimetric) == "absolute");

    for (const char* state : {"sending", "sent", "printed", "spoiled", "missed"})
        CHECK(jobs::to_string(*jobs::parse_tile_state(state)) == state);
    for (const char* status : {"queued", "printing", "done", "cancelled", "failed"})
        CHECK(jobs::to_string(*jobs::parse_job_status(status)) == status);
    CHECK_FALSE(jobs::parse_tile_state("Printed").has_value());

    CHECK(daemon::to_string(daemon::LineStatus::estop) == "e-stop");
    CHECK(daemon::to_string(daemon::LineStatus::paused) == "paused");

    CHECK(synth::parse_tile_layout("wall") == synth::TileLayout::Wall);
    CHECK(synth::tile_layout_name(synth::TileLayout::Scatter) == "scatter");
    CHECK_FALSE(synth::parse_tile_layout("grid").has_value());
    CHECK(synth::parse_synth_method("enm", "--method") == synth::SynthMethod::Enm);
    CHECK(synth::synth_method_name(synth::SynthMethod::Rsgf) == "rsgf");
    CHECK_THROWS_WITH(synth::parse_synth_method("patch", "--method"),
                      Catch::Contains("--method 'patch'"));
}
