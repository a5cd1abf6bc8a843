// tilejet line status: the line's state, read over Modbus from the PLC (or tilejet-linesim).

#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "tilejet/drivers/config.hpp"
#include "tilejet/drivers/modbus/modbus_line_control.hpp"

namespace tilejet::cli {

namespace {

void run_line_status(const std::string& config_path) {
    const auto config = drivers::load_drivers_config(config_path);
    drivers::ModbusLineControl line(config.modbus, config.registers);
    const auto values = line.read_all();
    nlohmann::ordered_json j;
    j["link"] = line.endpoint();
    // Named fields first (what an operator looks for), then every register in map order.
    const drivers::LineState s = line.read_state();
    j["ready"] = s.ready;
    j["running"] = s.running;
    j["estop"] = s.estop;
    j["fault_code"] = s.fault_code;
    j["speed_mm_s"] = s.speed_mm_s;
    j["speed_setpoint_mm_s"] = s.speed_setpoint_mm_s;
    j["tile_counter"] = s.tile_counter;
    nlohmann::ordered_json registers;
    for (const drivers::Register& r : config.registers.registers())
        registers[r.name] = values.at(r.name);
    j["registers"] = registers;
    std::printf("%s\n", j.dump(2).c_str());
}

}  // namespace

void add_line_commands(CLI::App& app) {
    CLI::App* line = app.add_subcommand("line", "the production line (PLC over Modbus)");
    line->require_subcommand(1);
    auto config = std::make_shared<std::string>("config/tilejet.toml");
    CLI::App* status = line->add_subcommand("status", "print the line's state as JSON");
    status->add_option("--config", *config, "config file (default config/tilejet.toml)");
    status->callback([config] { run_line_status(*config); });
}

}  // namespace tilejet::cli
