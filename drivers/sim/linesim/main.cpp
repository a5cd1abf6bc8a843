// tilejet-linesim: the production line in a process. A real Modbus TCP server (the PLC), a
// conveyor carrying tiles past a photo-eye to the heads, a simulated GPIO chip and print heads
// on Unix sockets, and a control socket for fault injection (tilejet sim ...).

#include <signal.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "line_simulator.hpp"

namespace {

std::atomic<bool> g_stop{false};

void on_signal(int) {
    g_stop = true;
}

bool is_loopback(const std::string& host) {
    return host == "localhost" || host == "::1" || host.starts_with("127.");
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"tilejet-linesim: a simulated tile line (PLC over Modbus TCP, GPIO, heads)"};
    std::string config_path = "config/tilejet.toml", print_log;
    app.add_option("--config", config_path, "config file ([line], [modbus], [gpio], [sim])");
    app.add_option("--print-log", print_log, "append one JSON line per tile at the heads here");
    CLI11_PARSE(app, argc, argv);
    try {
        const auto config = tilejet::drivers::load_drivers_config(config_path);
        // The simulator is a test fixture: it never listens beyond this machine.
        if (!is_loopback(config.modbus.host))
            throw std::runtime_error(config_path +
                                     ": [modbus] host: the simulator listens on "
                                     "loopback only, not '" +
                                     config.modbus.host + "'");
        struct sigaction action {};
        action.sa_handler = on_signal;
        sigaction(SIGTERM, &action, nullptr);
        sigaction(SIGINT, &action, nullptr);
        signal(SIGPIPE, SIG_IGN);
        tilejet::linesim::LineSimulator line(config, print_log);
        // One line on stdout says the sockets are up and which port the kernel chose when the
        // config asks for port 0 (tests run several simulators at once).
        nlohmann::ordered_json ready{
            {"ready", true},
            {"modbus", config.modbus.host + ":" + std::to_string(line.modbus_port())},
            {"modbus_port", line.modbus_port()},
            {"gpio_socket", config.sim.gpio_socket},
            {"head_socket", config.sim.head_socket},
            {"control_socket", config.sim.control_socket}};
        std::printf("%s\n", ready.dump().c_str());
        std::fflush(stdout);
        line.run(g_stop);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tilejet-linesim: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
