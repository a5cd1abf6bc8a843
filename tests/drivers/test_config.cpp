// Config sections and the register map file: defaults, and errors that name file, section, key
// and line.

#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "linesim_process.hpp"
#include "tilejet/drivers/config_parse.hpp"

using namespace tilejet;
using Catch::Matchers::Contains;

namespace {

std::string write(const test::TempDir& dir, const std::string& name, const std::string& text) {
    const std::string path = (dir.path() / name).string();
    std::ofstream(path) << text;
    return path;
}

const std::string kMap =
    std::string("register_map = \"") + TILEJET_SOURCE_DIR + "/config/registers.toml\"\n";

}  // namespace

TEST_CASE("the shipped config loads with the values it states", "[drivers][config]") {
    const auto c = drivers::load_drivers_config(TILEJET_SOURCE_DIR "/config/tilejet.toml");
    CHECK(c.modbus.host == "127.0.0.1");
    CHECK(c.modbus.port == 1502);
    CHECK(c.modbus.parity == 'E');
    CHECK(c.line.tile_pitch_mm == 400);
    CHECK(c.gpio.backend == "sim");
    CHECK(c.gpio.debounce == std::chrono::microseconds(2000));
    CHECK(c.sim.head_buffer_tiles == 2);
    CHECK(c.sim.head_checksums);
    CHECK(c.registers.registers().size() == 8);
    CHECK(c.registers.at("tile_counter").words() == 2);
    CHECK(c.registers.at("speed_setpoint").retain);
}

TEST_CASE("the simulator's sockets named without a folder are in a private runtime folder",
          "[drivers][config][security]") {
    const char* saved_runtime = std::getenv("RUNTIME_DIRECTORY");
    const char* saved_xdg = std::getenv("XDG_RUNTIME_DIR");
    const std::string keep_runtime = saved_runtime ? saved_runtime : "";
    const std::string keep_xdg = saved_xdg ? saved_xdg : "";
    const std::string shipped = TILEJET_SOURCE_DIR "/config/tilejet.toml";
    ::setenv("RUNTIME_DIRECTORY", "/run/tilejet:/run/other", 1);
    auto c = drivers::load_drivers_config(shipped);
    CHECK(c.sim.gpio_socket == "/run/tilejet/gpio.sock");
    CHECK(c.sim.head_socket == "/run/tilejet/heads.sock");
    CHECK(c.sim.control_socket == "/run/tilejet/control.sock");
    ::unsetenv("RUNTIME_DIRECTORY");
    ::setenv("XDG_RUNTIME_DIR", "/run/user/1000", 1);
    CHECK(drivers::load_drivers_config(shipped).sim.gpio_socket ==
          "/run/user/1000/tilejet-sim/gpio.sock");
    ::unsetenv("XDG_RUNTIME_DIR");
    // Never a folder every local user shares by name.
    CHECK(drivers::load_drivers_config(shipped).sim.gpio_socket ==
          "/tmp/tilejet-sim-" + std::to_string(::getuid()) + "/gpio.sock");
    // A path with a folder is taken as it is.
    test::TempDir dir;
    const auto own =
        write(dir, "own.toml", "[line]\n" + kMap + "[sim]\ngpio_socket = \"/srv/line/gpio.sock\"\n");
    CHECK(drivers::load_drivers_config(own).sim.gpio_socket == "/srv/line/gpio.sock");
    if (saved_runtime) ::setenv("RUNTIME_DIRECTORY", keep_runtime.c_str(), 1);
    if (saved_xdg) ::setenv("XDG_RUNTIME_DIR", keep_xdg.c_str(), 1);
}

TEST_CASE("an unknown key names file, section, key and line", "[drivers][config]") {
    test::TempDir dir;
    const auto path =
        write(dir, "bad.toml", "[line]\n" + kMap + "\n[modbus]\nport = 1502\nprot = 7\n");
    REQUIRE_THROWS_WITH(drivers::load_drivers_config(path),
                        Contains(path + ":6: [modbus] prot: unknown key"));
}

TEST_CASE("a wrong type names file, section, key and line", "[drivers][config]") {
    test::TempDir dir;
    const auto path =
        write(dir, "bad.toml", "[line]\n" + kMap + "[gpio]\ndebounce_us = \"fast\"\n");
    REQUIRE_THROWS_WITH(drivers::load_drivers_config(path),
                        Contains(path + ":4: [gpio] debounce_us: expected an integer, got string"));
}

TEST_CASE("out-of-range values and bad choices are errors", "[drivers][config]") {
    test::TempDir dir;
    auto path = write(dir, "a.toml", "[line]\n" + kMap + "[modbus]\nport = 70000\n");
    REQUIRE_THROWS_WITH(drivers::load_drivers_config(path),
                        Contains("[modbus] port: value 70000 is outside 0..65535"));
    path = write(dir, "b.toml", "[line]\n" + kMap + "[gpio]\nbackend = \"sysfs\"\n");
    REQUIRE_THROWS_WITH(drivers::load_drivers_config(path), Contains("[gpio] backend: \"sysfs\""));
    path = write(dir, "c.toml", "[line]\ntile_length_mm = 500\ntile_pitch_mm = 400\n" + kMap);
    REQUIRE_THROWS_WITH(drivers::load_drivers_config(path), Contains("[line] tile_pitch_mm"));
}

TEST_CASE("sections the drivers do not own are left alone", "[drivers][config]") {
    test::TempDir dir;
    const auto path =
        write(dir, "full.toml",
              "[colour]\nintent = \"perceptual\"\n[line]\n" + kMap + "[api]\nport = 8080\n");
    CHECK_NOTHROW(drivers::load_drivers_config(path));
}

TEST_CASE("a TOML syntax error names the file and line", "[drivers][config]") {
    test::TempDir dir;
    const auto path = write(dir, "syntax.toml", "[line]\nheads_mm = = 3\n");
    REQUIRE_THROWS_WITH(drivers::load_drivers_config(path), Contains(path + ":2:"));
}

TEST_CASE("register map files are validated", "[drivers][config]") {
    test::TempDir dir;
    const std::string good = [] {
        std::ifstream in(TILEJET_SOURCE_DIR "/config/registers.toml");
        return std::string(std::istreambuf_iterator<char>(in), {});
    }();
    SECTION("overlapping addresses") {
        const auto path = write(dir, "r.toml",
                                good +
                                    "\n[[register]]\nname = \"x\"\ntable = "
                                    "\"input\"\naddress = 5\ntype = \"u16\"\n"
                                    "meaning = \"collides with tile_counter\"\n");
        REQUIRE_THROWS_WITH(
            drivers::load_register_map(path),
            Contains("input register 5 'x' overlaps input register 4 'tile_counter'"));
    }
    SECTION("a register LineControl needs is missing") {
        std::string text = good;
        text.replace(text.find("name = \"estop\""), 14, "name = \"e_stop\"");
        const auto path = write(dir, "r.toml", text);
        REQUIRE_THROWS_WITH(drivers::load_register_map(path), Contains("no register 'estop'"));
    }
    SECTION("an unknown key in a register") {
        const auto path = write(dir, "r.toml",
                                good +
                                    "\n[[register]]\nname = \"x\"\ntable = "
                                    "\"holding\"\naddress = 200\ntype = \"u16\"\n"
                                    "meaning = \"m\"\nscale = 10\n");
        REQUIRE_THROWS_WITH(drivers::load_register_map(path), Contains("] scale: unknown key"));
    }
}
