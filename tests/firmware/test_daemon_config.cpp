// tilejetd's config: the shipped file loads; each kind of mistake stops the daemon with the file,
// the line, the section and the key.
#include <catch2/catch.hpp>
#include <fstream>
#include <sstream>

#include "../drivers/linesim_process.hpp"
#include "daemon_config.hpp"

using namespace tilejet;
using Catch::Matchers::Contains;

namespace {

std::string shipped_config() {
    std::ifstream in(TILEJET_SOURCE_DIR "/config/tilejet.toml");
    std::stringstream s;
    s << in.rdbuf();
    std::string text = s.str();
    // Relative paths resolve against the file's folder; the copy lives elsewhere, and the demo's
    // line profile is made by scripts/demo.
    const std::string map = "register_map = \"registers.toml\"";
    REQUIRE(text.find(map) != std::string::npos);
    text.replace(text.find(map), map.size(),
                 "register_map = \"" TILEJET_SOURCE_DIR "/config/registers.toml\"");
    const std::string profile = "output_profile = \"../out/demo/line-fogra39.icc\"";
    REQUIRE(text.find(profile) != std::string::npos);
    text.replace(text.find(profile), profile.size(),
                 "output_profile = \"" TILEJET_TEST_CMYK_PROFILE "\"");
    return text;
}

// The shipped config with `from` replaced by `to` (first occurrence after `after`).
std::string changed(const std::string& after, const std::string& from, const std::string& to) {
    std::string text = shipped_config();
    const auto at = text.find(from, text.find("\n" + after));  // the section, not a comment
    REQUIRE(at != std::string::npos);
    return text.replace(at, from.size(), to);
}

std::string load_error(const test::TempDir& dir, const std::string& text) {
    const auto path = (dir.path() / "tilejet.toml").string();
    std::ofstream(path) << text;
    try {
        daemon::load_daemon_config(path);
    } catch (const std::exception& e) {
        return e.what();
    }
    FAIL("the config was accepted");
    return {};
}

}  // namespace

TEST_CASE("the shipped daemon config loads", "[daemon][config]") {
    test::TempDir dir;
    const auto path = (dir.path() / "tilejet.toml").string();
    std::ofstream(path) << shipped_config();
    const auto c = daemon::load_daemon_config(path);
    CHECK(c.print.speed_mm_s == 500);
    CHECK(c.api.host == "127.0.0.1");
    CHECK(c.render.queue_tiles == 8);
}

TEST_CASE("daemon config mistakes name the file, line, section and key", "[daemon][config]") {
    test::TempDir dir;
    const std::string file = (dir.path() / "tilejet.toml").string();

    SECTION("an unknown key") {
        const auto e =
            load_error(dir, changed("[print]", "poll_ms = 5", "poll_ms = 5\npol_ms = 6"));
        CHECK_THAT(e, Contains(file) && Contains("[print]") && Contains("pol_ms"));
    }
    SECTION("an unknown section") {
        const auto e = load_error(dir, shipped_config() + "\n[printer]\nspeed = 1\n");
        CHECK_THAT(e, Contains(file) && Contains("printer"));
    }
    SECTION("a wrong type") {
        const auto e =
            load_error(dir, changed("[render]", "queue_tiles = 8", "queue_tiles = \"eight\""));
        CHECK_THAT(e, Contains("[render]") && Contains("queue_tiles"));
    }
    SECTION("a speed above the PLC's limit in the register map") {
        const auto e = load_error(dir, changed("[print]", "speed_mm_s = 500", "speed_mm_s = 2500"));
        CHECK_THAT(e, Contains("[print] speed_mm_s") && Contains("2000"));
    }
    SECTION("a slowest speed above the top speed") {
        const auto e =
            load_error(dir, changed("[print]", "min_speed_mm_s = 100", "min_speed_mm_s = 600"));
        CHECK_THAT(e, Contains("min_speed_mm_s"));
    }
    SECTION("broken TOML, with its line") {
        const auto e = load_error(dir, changed("[api]", "port = 8470", "port = = 8470"));
        const std::string text = shipped_config();
        const auto line =
            1 +
            std::count(text.begin(), text.begin() + std::ptrdiff_t(text.find("port = 8470")), '\n');
        CHECK_THAT(e, Contains(file + ":" + std::to_string(line)));
    }
}
