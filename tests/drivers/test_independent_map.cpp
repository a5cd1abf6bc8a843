// An independent check of the register map: Debian's mbpoll (not tilejet's client, not
// libmodbus's client code path in tilejet) reads the simulator at the addresses that
// drivers/REGISTERS.md documents, and the values must match the simulator's own state.

#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>
#include <map>
#include <regex>

#include "linesim_process.hpp"

using namespace tilejet;
using namespace std::chrono_literals;

namespace {

struct DocumentedRegister {
    int address;
    std::string table, name, type;
};

// The rows of the table in REGISTERS.md: "| 4–5 | input | `tile_counter` | u32 | ..."
std::vector<DocumentedRegister> documented() {
    std::ifstream in(TILEJET_SOURCE_DIR "/drivers/REGISTERS.md");
    const std::regex row(R"(^\| (\d+)(?:–\d+)? \| (input|holding) \| `(\w+)` \| (\w+))");
    std::vector<DocumentedRegister> rows;
    std::string line;
    std::smatch m;
    while (std::getline(in, line))
        if (std::regex_search(line, m, row)) rows.push_back({std::stoi(m[1]), m[2], m[3], m[4]});
    return rows;
}

std::string run(const std::string& command) {
    std::string out;
    FILE* p = popen(command.c_str(), "r");
    REQUIRE(p);
    char buffer[256];
    while (fgets(buffer, sizeof buffer, p))
        out += buffer;
    pclose(p);
    return out;
}

// mbpoll, once (-1), zero-based addresses (-0), 1 s timeout; returns "[addr]: value" pairs.
std::map<int, long> mbpoll(int port, const std::string& table, int address, int count,
                           const std::string& write = {}) {
    const std::string command = "timeout 5 mbpoll -m tcp -a 1 -p " + std::to_string(port) + " -t " +
                                (table == "input" ? "3" : "4") + " -r " + std::to_string(address) +
                                (write.empty() ? " -c " + std::to_string(count) : "") +
                                " -0 -1 -o 1 127.0.0.1 " + write + " 2>&1";
    const std::string out = run(command);
    std::map<int, long> values;
    const std::regex value(R"(\[(\d+)\]:\s+(-?\d+))");
    for (auto it = std::sregex_iterator(out.begin(), out.end(), value);
         it != std::sregex_iterator(); ++it)
        values[std::stoi((*it)[1])] = std::stol((*it)[2]);
    INFO(command << "\n" << out);
    CHECK((write.empty() ? values.size() == size_t(count)
                         : out.find("Written") != std::string::npos));
    return values;
}

}  // namespace

TEST_CASE("mbpoll reads the simulator at the addresses REGISTERS.md documents",
          "[drivers][modbus][independent]") {
    if (std::system("command -v mbpoll > /dev/null 2>&1") != 0) {
        WARN("SKIPPED: mbpoll is not installed (Debian package mbpoll; scripts/deps installs it)");
        return;
    }
    const auto rows = documented();
    REQUIRE(rows.size() == 8);  // the table documents every register of the map

    test::LinesimOptions o;
    o.speed_mm_s = 2000;
    test::LinesimProcess sim(o);
    // Put the line in a state where every register has a distinctive value.
    sim.control("start-conveyor");
    REQUIRE(test::eventually([&] { return sim.status()["tile_counter"] >= 3; }, 3s));
    sim.control("fault 513");  // stops the line, so the counter holds still
    const auto status = sim.status();

    std::map<std::string, long> expected{
        {"ready", 0},
        {"running", 0},
        {"fault_code", 513},
        {"speed_actual", 0},
        {"tile_counter", status["tile_counter"].get<long>()},
        {"estop", 0},
        {"speed_setpoint", 2000},
        {"run_command", 0},
    };
    for (const auto& r : rows) {
        INFO(r.name);
        REQUIRE(expected.contains(r.name));
        const int words = r.type == "u32" ? 2 : 1;
        const auto v = mbpoll(sim.port(), r.table, r.address, words);
        const long value =
            words == 2 ? (v.at(r.address) << 16) | v.at(r.address + 1) : v.at(r.address);
        CHECK(value == expected[r.name]);
    }

    // Writing through the documented address reaches the simulator's register.
    for (const auto& r : rows)
        if (r.name == "speed_setpoint") mbpoll(sim.port(), r.table, r.address, 1, "1500");
    CHECK(sim.status()["speed_setpoint"] == 1500);
}
