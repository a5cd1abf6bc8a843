// The config library every module's parser is written with, on broken input: each mistake names
// the file and line, and the section and key where there is one.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "../temp_dir.hpp"
#include "tilejet/config/known_sections.hpp"
#include "tilejet/config/paths.hpp"
#include "tilejet/config/section.hpp"
#include "tilejet/config/toml_file.hpp"

using namespace tilejet;
using Catch::Matchers::Contains;
using Catch::Matchers::Equals;

namespace {

std::string write(const test::TempDir& dir, const std::string& text) {
    const std::string path = (dir.path() / "line.toml").string();
    std::ofstream(path) << text;
    return path;
}

}  // namespace

TEST_CASE("a section is a table, absent, or an error naming file and line", "[config]") {
    test::TempDir dir;
    const auto path = write(dir, "# the line\nline = 5\n\n[print]\nspeed_mm_s = 300\n");
    const toml::table root = config::load_toml_file(path);
    const config::ConfigSource source{path};
    CHECK(config::find_section(root, "print", source) != nullptr);
    CHECK(config::find_section(root, "render", source) == nullptr);
    REQUIRE_THROWS_WITH(config::find_section(root, "line", source),
                        Equals(path + ":2: 'line' must be a [line] section"));
}

TEST_CASE("a key nobody read is an unknown key, with its line", "[config]") {
    test::TempDir dir;
    const auto path = write(dir, "[render]\ndpi = 300\ndpl = 3\n");
    const toml::table root = config::load_toml_file(path);
    config::ConfigSection s(config::find_section(root, "render", {path}), {path}, "render");
    CHECK(s.get_int("dpi", 360, 10, 2400) == 300);
    REQUIRE_THROWS_WITH(s.finish(), Equals(path + ":3: [render] dpl: unknown key"));
}

TEST_CASE("a value of the wrong type or out of range names section, key and line", "[config]") {
    test::TempDir dir;
    const auto path = write(dir,
                            "[modbus]\nhost = 127\nport = 70000\nbaud = 19200\n"
                            "parity = \"X\"\nenabled = \"yes\"\n");
    const toml::table root = config::load_toml_file(path);
    config::ConfigSection s(root["modbus"].as_table(), {path}, "modbus");
    REQUIRE_THROWS_WITH(s.get_string("host", "localhost"),
                        Equals(path + ":2: [modbus] host: expected a string, got integer"));
    REQUIRE_THROWS_WITH(s.get_int("port", 1502, 0, 65535),
                        Equals(path + ":3: [modbus] port: value 70000 is outside 0..65535"));
    CHECK(s.get_int("baud", 9600, 1200, 1000000) == 19200);
    REQUIRE_THROWS_WITH(
        s.get_choice("parity", "E", {"N", "E", "O"}),
        Equals(path + ":5: [modbus] parity: \"X\" is not one of \"N\", \"E\", \"O\""));
    REQUIRE_THROWS_WITH(s.get_bool("enabled", false),
                        Equals(path + ":6: [modbus] enabled: expected true or false, got string"));
}

TEST_CASE("absent keys take their defaults and a required one names the file and section",
          "[config]") {
    test::TempDir dir;
    const auto path = write(dir, "[print]\nspeed_mm_s = 300\n");
    const toml::table root = config::load_toml_file(path);
    config::ConfigSection s(config::find_section(root, "colour", {path}), {path}, "colour");
    CHECK(s.get_double("ink_limit_percent", 300, 0, 400) == 300);
    CHECK(s.get_string("intent", "perceptual") == "perceptual");
    CHECK_NOTHROW(s.finish());
    REQUIRE_THROWS_WITH(s.require_string("output_profile"),
                        Equals(path + ": [colour] output_profile: missing (required)"));
}

TEST_CASE("relative paths resolve against the config file's folder", "[config]") {
    const config::ConfigSource source{"/etc/tilejet/line/tilejet.toml"};
    CHECK(config::resolve_path(source, "registers.toml") == "/etc/tilejet/line/registers.toml");
    CHECK(config::resolve_path(source, "../profiles/line.icc") == "/etc/tilejet/profiles/line.icc");
    CHECK(config::resolve_path(source, "/var/lib/tilejet/jobs.db") == "/var/lib/tilejet/jobs.db");
    CHECK(config::resolve_path(source, "").empty());  // an optional path left out stays out
    CHECK(config::resolve_path({"tilejet.toml"}, "registers.toml") == "registers.toml");
}

TEST_CASE("a section no module claims is an unknown section, with its line", "[config]") {
    test::TempDir dir;
    const auto path = write(dir, "[line]\nheads_mm = 600\n\n[printer]\nspeed = 1\n");
    const toml::table root = config::load_toml_file(path);
    CHECK_NOTHROW(config::reject_unknown_sections(root, {"line", "printer"}, {path}));
    REQUIRE_THROWS_WITH(config::reject_unknown_sections(root, {"line", "print"}, {path}),
                        Equals(path + ":4: [printer]: unknown section"));
}

TEST_CASE("a TOML syntax error names the file and line", "[config]") {
    test::TempDir dir;
    const auto path = write(dir, "[line]\nheads_mm = 600\ntile_pitch_mm = = 400\n");
    REQUIRE_THROWS_WITH(config::load_toml_file(path), Contains(path + ":3:"));
}
