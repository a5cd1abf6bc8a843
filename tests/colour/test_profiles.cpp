// Profiles and measurements as engineers bring them, and profiles built from measurements.

#include <catch2/catch.hpp>
#include <fstream>
#include <iterator>
#include <sstream>

#include "../synth/fixtures.hpp"
#include "colour_fixtures.hpp"
#include "tilejet/colour/cmyk_transform.hpp"
#include "tilejet/colour/measurements.hpp"
#include "tilejet/colour/profile_builder.hpp"
#include "tilejet/colour/profile_report.hpp"

using namespace tilejet;
using Catch::Matchers::Contains;

namespace {

std::string slurp(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string transform_error(const std::filesystem::path& output) {
    colour::ColourSettings s;
    s.output_profile = output;
    try {
        colour::CmykTransform t(s);
    } catch (const colour::ColourError& e) {
        return e.what();
    }
    return "";
}

// FOGRA39L.ti3 with one field renamed in its data format line.
std::filesystem::path without_field(const test::TempDir& dir, const std::string& field) {
    std::string text = slurp(test::fogra39_measurements());
    const size_t format = text.find("BEGIN_DATA_FORMAT");
    REQUIRE(format != std::string::npos);
    const size_t at = text.find(" " + field, format);
    REQUIRE(at != std::string::npos);
    text.replace(at + 1, field.size(), "XX" + field.substr(2));
    const auto path = dir / ("no-" + field + ".ti3");
    test::write_file(path, text);
    return path;
}

}  // namespace

TEST_CASE("unusable output profiles fail naming the file", "[colour][profile]") {
    test::TempDir dir;
    test::write_file(dir / "notes.icc", "this is a text file, not a profile\n");
    REQUIRE_THAT(transform_error(dir / "notes.icc"),
                 Contains("notes.icc") && Contains("not an ICC profile"));

    REQUIRE_THAT(transform_error("/usr/share/color/icc/sRGB.icc"),
                 Contains("sRGB.icc") && Contains("RGB") && Contains("must be CMYK"));

    const std::string good = slurp(test::test_cmyk_profile());
    test::write_file(dir / "half.icc", good.substr(0, good.size() / 2));
    REQUIRE_THAT(transform_error(dir / "half.icc"), Contains("half.icc") && Contains("truncated"));

    REQUIRE_THAT(transform_error(dir / "missing.icc"),
                 Contains("missing.icc") && Contains("cannot read"));

    // Regression (fuzzing): a colour space outside LittleCMS's enum was undefined behaviour.
    std::string odd_space = good;
    odd_space.replace(16, 4, "\xFF\xFF\xFF\xFF");
    test::write_file(dir / "odd-space.icc", odd_space);
    REQUIRE_THAT(transform_error(dir / "odd-space.icc"),
                 Contains("odd-space.icc") && Contains("unsupported colour space"));

    std::string damaged = good;  // a valid header over garbage tags
    for (size_t i = 132; i < damaged.size(); ++i)
        damaged[i] = char(0xA5);
    test::write_file(dir / "damaged.icc", damaged);
    REQUIRE_THAT(transform_error(dir / "damaged.icc"), Contains("damaged.icc"));
}

TEST_CASE("measurements missing their Lab or CMYK fields fail naming file and field",
          "[colour][profile]") {
    test::TempDir dir;
    REQUIRE(colour::read_measurements(test::fogra39_measurements()).size() == 1617);
    for (const std::string field : {"LAB_L", "LAB_B", "CMYK_C", "CMYK_K"}) {
        const auto path = without_field(dir, field);
        REQUIRE_THROWS_WITH(colour::read_measurements(path),
                            Contains(path.filename().string()) && Contains(field));
    }
    test::write_file(dir / "junk.ti3", "\x01\x02 not CGATS at all");
    REQUIRE_THROWS_WITH(colour::read_measurements(dir / "junk.ti3"), Contains("junk.ti3"));
}

TEST_CASE("measurements whose patch count the data does not bear out fail naming the file",
          "[colour][profile]") {
    test::TempDir dir;
    // Regression (fuzzing, tests/fuzz/corpus/fuzz_measurements/regression-huge-number-of-sets):
    // NUMBER_OF_SETS 4.3e19 was converted to int, undefined behaviour.
    const auto crash = std::filesystem::path(TILEJET_SOURCE_DIR) /
                       "tests/fuzz/corpus/fuzz_measurements/regression-huge-number-of-sets";
    REQUIRE_THROWS_WITH(colour::read_measurements(crash),
                        Contains("regression-huge-number-of-sets") && Contains("NUMBER_OF_SETS"));

    std::string text = slurp(test::fogra39_measurements());
    const std::string sets = "NUMBER_OF_SETS 1617";
    const size_t at = text.find(sets);
    REQUIRE(at != std::string::npos);
    std::string more = text;
    more.replace(at, sets.size(), "NUMBER_OF_SETS 1618");  // one patch more than the data
    test::write_file(dir / "more.ti3", more);
    REQUIRE_THROWS_WITH(colour::read_measurements(dir / "more.ti3"),
                        Contains("more.ti3") && Contains("NUMBER_OF_SETS"));
    const size_t data = text.find("BEGIN_DATA\r\n");  // CRLF lines
    REQUIRE(data != std::string::npos);
    test::write_file(dir / "no-data.ti3", text.substr(0, data));  // the format, then nothing
    REQUIRE_THROWS_WITH(colour::read_measurements(dir / "no-data.ti3"),
                        Contains("no-data.ti3") && Contains("patch 1 of 1617"));
    std::string huge = text;
    huge.replace(at, sets.size(), "NUMBER_OF_SETS 2000000000");
    test::write_file(dir / "huge.ti3", huge);
    REQUIRE_THROWS_WITH(colour::read_measurements(dir / "huge.ti3"), Contains("huge.ti3"));
}

TEST_CASE("a profile built from FOGRA39L measurements predicts them within 1.5 dE2000",
          "[colour][profile][slow]") {
    test::TempDir dir;
    colour::ProfileBuildOptions options;
    options.quality = "m";
    colour::build_profile(test::fogra39_measurements(), dir / "line.icc", options);
    const colour::ProfileReport report = colour::check_profile(
        dir / "line.icc", colour::read_measurements(test::fogra39_measurements()));
    WARN("FOGRA39L profile: mean dE2000 " << report.mean << ", p95 " << report.p95 << ", max "
                                          << report.max << " over " << report.patches
                                          << " patches");
    REQUIRE(report.patches == 1617);
    REQUIRE(report.mean <= 1.5);
    REQUIRE(report.max >= report.p95);
    REQUIRE(report.p95 >= report.mean * 0.5);
}

TEST_CASE("the report is not blind: a profile for other measurements scores worse",
          "[colour][profile]") {
    // FOGRA28L is newsprint-like uncoated paper: the coated FOGRA39 profile must miss it widely.
    const auto other = colour::read_measurements("/usr/share/color/icc/FOGRA28L.ti3");
    const auto own = colour::read_measurements(test::fogra39_measurements());
    const auto good = colour::check_profile(test::test_cmyk_profile(), own);
    const auto bad = colour::check_profile(test::test_cmyk_profile(), other);
    INFO("own " << good.mean << ", other " << bad.mean);
    REQUIRE(bad.mean > 3 * good.mean);
}

TEST_CASE("profile build refuses bad measurements before running colprof", "[colour][profile]") {
    test::TempDir dir;
    const auto path = without_field(dir, "LAB_A");
    REQUIRE_THROWS_WITH(colour::build_profile(path, dir / "x.icc", {}), Contains("LAB_A"));
    REQUIRE_FALSE(std::filesystem::exists(dir / "x.icc"));
}
