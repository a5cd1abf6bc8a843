#include "tilejet/drivers/sim/sim_gpio_lines.hpp"

#include <sstream>
#include <stdexcept>

#include "unix_socket.hpp"

namespace tilejet::drivers::sim {

namespace {

constexpr std::chrono::milliseconds kConnectTimeout{2000};

std::optional<GpioInput> input_named(const std::string& name) {
    for (GpioInput i : kGpioInputs)
        if (config_key(i) == name) return i;
    return std::nullopt;
}

}  // namespace

SimGpioLines::SimGpioLines(const std::string& socket_path)
    : socket_(std::make_unique<UnixSocket>(
          UnixSocket::connect(socket_path, "sim gpio chip " + socket_path, kConnectTimeout))) {
    // The chip greets with the level of every input, then READY.
    while (true) {
        auto line = socket_->read_line(kConnectTimeout);
        if (!line) throw std::runtime_error(socket_->what() + ": no greeting within 2 s");
        if (*line == "READY") break;
        parse(*line);
    }
}

SimGpioLines::~SimGpioLines() = default;

std::optional<RawEdge> SimGpioLines::parse(const std::string& line) {
    std::istringstream in(line);
    std::string kind, name;
    int level = -1;
    long long ns = -1;
    in >> kind >> name >> level >> ns;
    const auto input = input_named(name);
    if (!in || (kind != "EDGE" && kind != "LEVEL") || !input || (level != 0 && level != 1))
        throw std::runtime_error(socket_->what() + ": malformed message '" + line + "'");
    std::lock_guard lock(mutex_);
    levels_[size_t(*input)] = level == 1;
    if (kind == "LEVEL") return std::nullopt;
    return RawEdge{*input, level == 1, std::chrono::nanoseconds(ns)};
}

std::optional<RawEdge> SimGpioLines::wait_edge(std::chrono::microseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (true) {
        const auto left = std::chrono::duration_cast<std::chrono::microseconds>(
            deadline - std::chrono::steady_clock::now());
        auto line = socket_->read_line(std::max(left, std::chrono::microseconds(0)));
        if (!line) return std::nullopt;
        if (auto edge = parse(*line)) return edge;
    }
}

bool SimGpioLines::read(GpioInput input) {
    std::lock_guard lock(mutex_);
    return levels_[size_t(input)];
}

void SimGpioLines::write(GpioOutput output, bool level) {
    socket_->send_all("SET " + std::string(config_key(output)) + (level ? " 1\n" : " 0\n"),
                      std::chrono::milliseconds(500));
}

}  // namespace tilejet::drivers::sim
