// tilejet line status and tilejet sim ..., run as a user would, against tilejet-linesim.

#include <catch2/catch.hpp>
#include <cstdio>

#include "linesim_process.hpp"

using namespace tilejet;

namespace {

struct Result {
    int status;
    std::string out;
};

Result run(const std::string& arguments) {
    const std::string command =
        std::string("timeout 10 ") + TILEJET_CLI + " " + arguments + " 2>&1";
    FILE* p = popen(command.c_str(), "r");
    REQUIRE(p);
    std::string out;
    char buffer[512];
    while (fgets(buffer, sizeof buffer, p))
        out += buffer;
    const int status = pclose(p);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

}  // namespace

TEST_CASE("tilejet line status prints the line's state as JSON", "[drivers][cli]") {
    test::LinesimProcess sim;
    const auto r = run("line status --config " + sim.config_path());
    INFO(r.out);
    REQUIRE(r.status == 0);
    const auto j = nlohmann::json::parse(r.out);
    CHECK(j["link"] == "tcp 127.0.0.1:" + std::to_string(sim.port()));
    CHECK(j["ready"] == true);
    CHECK(j["running"] == false);
    CHECK(j["speed_setpoint_mm_s"] == 1000);
    CHECK(j["registers"].size() == 8);
    CHECK(j["registers"]["speed_setpoint"] == 1000);
}

TEST_CASE("tilejet sim injects faults that tilejet line status then reports", "[drivers][cli]") {
    test::LinesimProcess sim;
    const std::string config = " --config " + sim.config_path();
    REQUIRE(run("sim fault 9" + config).status == 0);
    REQUIRE(run("sim estop on" + config).status == 0);
    auto j = nlohmann::json::parse(run("line status" + config).out);
    CHECK(j["fault_code"] == 9);
    CHECK(j["estop"] == true);
    CHECK(j["ready"] == false);
    REQUIRE(run("sim fault clear" + config).status == 0);
    REQUIRE(run("sim estop off" + config).status == 0);
    REQUIRE(run("sim start-conveyor" + config).status == 0);
    j = nlohmann::json::parse(run("line status" + config).out);
    CHECK(j["running"] == true);
    REQUIRE(run("sim stop-conveyor" + config).status == 0);
    REQUIRE(run("sim delay 20" + config).status == 0);
    REQUIRE(run("sim glitch" + config).status == 0);
    REQUIRE(run("sim drop-link 0.1" + config).status == 0);
    const auto status = sim.status();
    CHECK(status["delay_ms"] == 20);
    CHECK(status["running"] == false);
    // A bad argument is an error from the simulator, with a non-zero exit.
    const auto bad = run("sim fault banana" + config);
    CHECK(bad.status != 0);
    CHECK_THAT(bad.out, Catch::Matchers::Contains("bad number"));
}

TEST_CASE("tilejet line status without a line says which link failed", "[drivers][cli]") {
    test::TempDir dir;
    std::string config;
    {
        test::LinesimProcess sim;
        config = sim.config_path();
        // Copy the config out: the simulator's folder goes away with it.
        std::filesystem::copy_file(config, dir.path() / "line.toml");
    }
    const auto r = run("line status --config " + (dir.path() / "line.toml").string());
    CHECK(r.status != 0);
    CHECK_THAT(r.out, Catch::Matchers::Contains("cannot connect"));
}
