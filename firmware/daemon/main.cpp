// tilejetd: the print controller. Takes jobs over the API, renders tiles ahead of the conveyor
// and hands them to the heads exactly once per tile, through crashes, e-stops and link loss.
#include <signal.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <thread>

#include "daemon_api.hpp"
#include "daemon_config.hpp"
#include "line_state.hpp"
#include "print_loop.hpp"
#include "service_notify.hpp"
#include "tilejet/api/api_server.hpp"

namespace {

using namespace tilejet::daemon;
using namespace std::chrono_literals;

// SIGHUP: what can change without a restart is the [print] section (speeds, timing); the
// others own open resources (drivers, database, API socket, render pool) and need a restart.
void reload(const std::string& path, const DaemonConfig& running, PrintLoop& loop) {
    try {
        const DaemonConfig fresh = load_daemon_config(path);
        loop.reload(fresh.print);
        if (fresh.storage.database != running.storage.database ||
            fresh.api.port != running.api.port || fresh.render.threads != running.render.threads ||
            fresh.drivers.modbus.port != running.drivers.modbus.port)
            log_line(
                "SIGHUP: [storage], [api], [render] and the drivers' sections take effect "
                "after a restart");
    } catch (const std::exception& e) {
        log_line("SIGHUP: config not reloaded: " + std::string(e.what()));
    }
}

int run(const std::string& config_path) {
    const DaemonConfig config = load_daemon_config(config_path);
    std::filesystem::create_directories(
        std::filesystem::absolute(config.storage.database).parent_path());
    std::filesystem::create_directories(config.storage.previews);

    // Signals are taken by this thread only (sigtimedwait), never by the loop or the API.
    sigset_t signals;
    sigemptyset(&signals);
    for (int s : {SIGTERM, SIGINT, SIGHUP})
        sigaddset(&signals, s);
    pthread_sigmask(SIG_BLOCK, &signals, nullptr);
    signal(SIGPIPE, SIG_IGN);

    Controller controller;
    PrintLoop loop(config, controller);
    DaemonApi backend(config, controller);
    tilejet::api::ApiServer server(backend, config.api.host, config.api.port);
    std::thread line_thread([&] { loop.run(); });

    const std::string address = config.api.host + ":" + std::to_string(server.port());
    log_line("API on http://" + address + ", job store " + config.storage.database);
    std::printf("%s\n",
                nlohmann::json{{"ready", true}, {"api", address}, {"api_port", server.port()}}
                    .dump()
                    .c_str());
    std::fflush(stdout);
    notify_ready("API on " + address);

    const auto watchdog = watchdog_interval();
    const auto wait = watchdog ? std::min<std::chrono::microseconds>(*watchdog, 1s)
                               : std::chrono::microseconds(1s);
    while (true) {
        const auto secs = std::chrono::duration_cast<std::chrono::seconds>(wait);
        timespec timeout{secs.count(), long((wait - secs).count() * 1000)};
        const int sig = sigtimedwait(&signals, nullptr, &timeout);
        if (sig == SIGTERM || sig == SIGINT) {
            notify_stopping();
            controller.terminate = true;
            break;
        }
        if (sig == SIGHUP) reload(config_path, config, loop);
        // Ping only while the print loop turns: a stuck loop must get the daemon restarted.
        const auto beat = std::chrono::nanoseconds(controller.heartbeat_ns.load());
        const auto now = std::chrono::steady_clock::now().time_since_epoch();
        if (watchdog && now - beat < 5s) notify_watchdog();
        const auto s = controller.snapshot();
        notify_status(std::string(to_string(s.status)) + ": " + s.reason);
    }
    line_thread.join();
    log_line("stopped");
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"tilejetd: the tilejet print controller"};
    std::string config_path = "/etc/tilejet/tilejet.toml";
    app.add_option("--config", config_path, "config file (TOML)");
    CLI11_PARSE(app, argc, argv);
    try {
        return run(config_path);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tilejetd: error: %s\n", e.what());
        return 1;
    }
}
