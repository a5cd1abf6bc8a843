#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "tilejet/quality/quality_gates.hpp"

using tilejet::quality::gates_json;
using tilejet::quality::quality_gates;

namespace {

// A method's metrics as eval writes them: its periodicity (a number, or null where the
// exemplar's quilt had no peak) and its wall's highest peak.
nlohmann::ordered_json method(nlohmann::ordered_json periodicity, double peak) {
    nlohmann::ordered_json j;
    j["periodicity"] = periodicity;
    j["periodicity_peak"] = {{"value", peak}, {"lag", {640, 0}}};
    j["texture_energy"] = 1.0;
    return j;
}

}  // namespace

TEST_CASE("periodicity against the exemplar's quilt when that has a peak") {
    const auto gates = quality_gates(method(0.9, 0.30), method(1.5, 0.10), 0);
    REQUIRE(gates.periodicity);
    CHECK(*gates.periodicity == Approx(0.9));
    CHECK_FALSE(gates.periodicity_against_quilt_wall);
    CHECK(gates.periodicity_pass());
    CHECK(gates_json(gates)["periodicity_reference"] == "exemplar quilted");
}

TEST_CASE("periodicity against the quilting wall when the exemplar's quilt has no peak") {
    // The 8192 px slab: the wall's peak 0.21, the quilting wall's 0.24, the reference none.
    const double own = 0.21, baseline = 0.24;
    const auto below = quality_gates(method(nullptr, own), method(nullptr, baseline), 0);
    REQUIRE(below.periodicity);
    CHECK(*below.periodicity == Approx(own / baseline));
    CHECK(below.periodicity_against_quilt_wall);
    CHECK(below.periodicity_pass());
    CHECK(gates_json(below)["periodicity_reference"] == "quilting baseline wall");
    // A wall twice as periodic as quilting's fails.
    const auto above = quality_gates(method(nullptr, 2 * baseline), method(nullptr, baseline), 0);
    REQUIRE(above.periodicity);
    CHECK_FALSE(above.periodicity_pass());
}

TEST_CASE("no periodicity when nothing has a peak to compare with") {
    SECTION("the quilting wall's highest peak is not above zero") {
        const auto g = quality_gates(method(nullptr, 0.2), method(nullptr, -0.05), 0);
        CHECK_FALSE(g.periodicity);
        CHECK_FALSE(g.periodicity_pass());
        CHECK(gates_json(g)["periodicity"].is_null());
    }
    SECTION("the peaks are missing or not numbers") {
        nlohmann::ordered_json broken = method(nullptr, 0.2);
        broken["periodicity_peak"]["value"] = "high";
        CHECK_FALSE(quality_gates(broken, method(nullptr, 0.2), 0).periodicity);
        nlohmann::ordered_json missing = method(nullptr, 0.2);
        missing.erase("periodicity_peak");
        CHECK_FALSE(quality_gates(method(nullptr, 0.2), missing, 0).periodicity);
        nlohmann::ordered_json scalar = method(nullptr, 0.2);
        scalar["periodicity_peak"] = 3;
        CHECK_FALSE(quality_gates(scalar, method(nullptr, 0.2), 0).periodicity);
        CHECK_FALSE(quality_gates(scalar, method(nullptr, 0.2), 0).pass());
    }
}
