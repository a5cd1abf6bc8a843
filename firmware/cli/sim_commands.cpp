// tilejet sim ...: fault injection into tilejet-linesim through its control socket.

#include <cstdio>
#include <memory>
#include <vector>

#include "commands.hpp"
#include "tilejet/drivers/config.hpp"
#include "tilejet/drivers/sim/sim_control.hpp"

namespace tilejet::cli {

namespace {

struct SimOptions {
    std::string config = "config/tilejet.toml";
    std::string argument;
};

void send(const SimOptions& o, const std::string& request) {
    const auto config = drivers::load_drivers_config(o.config);
    drivers::sim::SimControl control(config.sim.control_socket);
    std::printf("%s\n", control.request(request).c_str());
}

// One subcommand: `verb` alone, or `verb ARG` when `arg_name` is given.
void add(CLI::App* sim, const std::string& verb, const std::string& help,
         const std::string& arg_name = {}, const std::string& arg_help = {},
         bool arg_required = true) {
    auto o = std::make_shared<SimOptions>();
    CLI::App* c = sim->add_subcommand(verb, help);
    c->add_option("--config", o->config, "config file (default config/tilejet.toml)");
    if (!arg_name.empty()) c->add_option(arg_name, o->argument, arg_help)->required(arg_required);
    c->callback([o, verb] { send(*o, o->argument.empty() ? verb : verb + " " + o->argument); });
}

}  // namespace

void add_sim_commands(CLI::App& app) {
    CLI::App* sim = app.add_subcommand("sim", "inject faults into tilejet-linesim");
    sim->require_subcommand(1);
    add(sim, "estop", "press (on) or release (off) the e-stop", "STATE", "on or off");
    add(sim, "fault", "raise a PLC fault code, or clear it", "CODE", "1..65535 or clear");
    add(sim, "drop-link", "reset the Modbus link and refuse it for SECONDS", "SECONDS",
        "seconds (fractions allowed)");
    add(sim, "delay", "answer every Modbus request MS late (0: on time)", "MS", "milliseconds");
    add(sim, "glitch", "a short spurious pulse on the photo-eye", "US",
        "pulse width in microseconds (default 300)", false);
    add(sim, "heads-reset", "the print heads restart and lose the tiles they hold");
    add(sim, "stop-conveyor", "stop the conveyor from the line side");
    add(sim, "start-conveyor", "start the conveyor from the line side");
    add(sim, "status", "print the simulator's state as JSON");
}

}  // namespace tilejet::cli
