#pragma once

// LinesimProcess: tilejet-linesim started as a separate process for one test, on a port the
// kernel picks (config port 0, reported on its first stdout line) and sockets in a private temp
// folder, so tests run in parallel. The destructor always kills and reaps it.

#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "../child_process.hpp"
#include "../temp_dir.hpp"
#include "tilejet/drivers/config.hpp"
#include "tilejet/drivers/sim/sim_control.hpp"

namespace tilejet::test {

struct LinesimOptions {
    double speed_mm_s = 1000;
    bool start_running = false;
    double tile_length_mm = 100, tile_pitch_mm = 200, photo_eye_mm = 50, heads_mm = 250;
    int head_buffer_tiles = 2;
    bool head_checksums = true;
    int response_timeout_ms = 200;
    int debounce_us = 2000;
    std::string register_map = TILEJET_SOURCE_DIR "/config/registers.toml";
};

class LinesimProcess {
  public:
    explicit LinesimProcess(const LinesimOptions& o = {}) {
        config_path_ = (dir_.path() / "line.toml").string();
        print_log_ = (dir_.path() / "print.log").string();
        write_config(o, 0);
        int out[2];
        if (pipe(out) != 0) throw std::runtime_error("pipe failed");
        child_.pid = fork();
        if (child_.pid == 0) {
            dup2(out[1], STDOUT_FILENO);
            detach_from_test();
            execl(TILEJET_LINESIM, TILEJET_LINESIM, "--config", config_path_.c_str(), "--print-log",
                  print_log_.c_str(), static_cast<char*>(nullptr));
            _exit(127);
        }
        close(out[1]);
        child_.stdout_fd = out[0];
        const std::string line = read_ready_line(std::chrono::seconds(5));
        const auto ready = nlohmann::json::parse(line);
        port_ = ready.at("modbus_port").get<int>();
        // The clients' config: the same file with the port the simulator got.
        write_config(o, port_);
        config_ = drivers::load_drivers_config(config_path_);
    }

    LinesimProcess(const LinesimProcess&) = delete;
    LinesimProcess& operator=(const LinesimProcess&) = delete;

    const drivers::DriversConfig& config() const { return *config_; }
    const std::string& config_path() const { return config_path_; }
    int port() const { return port_; }
    const std::string& print_log_path() const { return print_log_; }

    // A control-socket request; throws if the simulator says it failed.
    nlohmann::json control(const std::string& request) const {
        return nlohmann::json::parse(
            drivers::sim::SimControl(config_->sim.control_socket).request(request));
    }
    nlohmann::json status() const { return control("status"); }

    // The print log, one parsed JSON object per line.
    std::vector<nlohmann::json> print_log() const {
        std::vector<nlohmann::json> lines;
        std::ifstream in(print_log_);
        std::string line;
        while (std::getline(in, line))
            lines.push_back(nlohmann::json::parse(line));
        return lines;
    }

  private:
    void write_config(const LinesimOptions& o, int port) const {
        const std::string d = dir_.path().string();
        std::ofstream f(config_path_);
        f << "[line]\n"
          << "tile_length_mm = " << o.tile_length_mm << "\n"
          << "tile_pitch_mm = " << o.tile_pitch_mm << "\n"
          << "photo_eye_mm = " << o.photo_eye_mm << "\n"
          << "heads_mm = " << o.heads_mm << "\n"
          << "register_map = \"" << o.register_map << "\"\n"
          << "[modbus]\nhost = \"127.0.0.1\"\nport = " << port << "\n"
          << "response_timeout_ms = " << o.response_timeout_ms << "\n"
          << "reconnect_min_ms = 20\nreconnect_max_ms = 200\n"
          << "[gpio]\nbackend = \"sim\"\ndebounce_us = " << o.debounce_us << "\n"
          << "[sim]\n"
          << "gpio_socket = \"" << d << "/gpio.sock\"\n"
          << "head_socket = \"" << d << "/heads.sock\"\n"
          << "control_socket = \"" << d << "/control.sock\"\n"
          << "speed_mm_s = " << int(o.speed_mm_s) << "\n"
          << "start_running = " << (o.start_running ? "true" : "false") << "\n"
          << "head_buffer_tiles = " << o.head_buffer_tiles << "\n"
          << "head_checksums = " << (o.head_checksums ? "true" : "false") << "\n";
    }

    std::string read_ready_line(std::chrono::milliseconds timeout) {
        std::string text;
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        while (text.find('\n') == std::string::npos) {
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                deadline - std::chrono::steady_clock::now());
            pollfd p{child_.stdout_fd, POLLIN, 0};
            if (left.count() <= 0 || poll(&p, 1, int(left.count())) <= 0)
                throw std::runtime_error("tilejet-linesim did not report ready within 5 s");
            char buffer[512];
            const ssize_t n = read(child_.stdout_fd, buffer, sizeof buffer);
            if (n <= 0) throw std::runtime_error("tilejet-linesim exited before it was ready");
            text.append(buffer, size_t(n));
        }
        return text.substr(0, text.find('\n'));
    }

    TempDir dir_;
    std::string config_path_, print_log_;
    // Killed and reaped even when the constructor throws after the fork.
    struct Child {
        pid_t pid = -1;
        int stdout_fd = -1;
        ~Child() {
            if (pid > 0) {
                kill(pid, SIGTERM);
                const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
                while (waitpid(pid, nullptr, WNOHANG) == 0) {
                    if (std::chrono::steady_clock::now() > deadline) {
                        kill(pid, SIGKILL);
                        waitpid(pid, nullptr, 0);
                        break;
                    }
                    std::this_thread::sleep_for(std::chrono::milliseconds(5));
                }
            }
            if (stdout_fd >= 0) close(stdout_fd);
        }
    } child_;
    int port_ = 0;
    std::optional<drivers::DriversConfig> config_;
};

// Polls `condition` every 10 ms until it holds or `timeout` passes.
template <class F>
bool eventually(F condition, std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
        if (condition()) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return condition();
}

}  // namespace tilejet::test
