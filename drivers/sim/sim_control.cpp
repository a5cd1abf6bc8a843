#include "tilejet/drivers/sim/sim_control.hpp"

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "unix_socket.hpp"

namespace tilejet::drivers::sim {

SimControl::SimControl(std::string socket_path, std::chrono::milliseconds timeout)
    : path_(std::move(socket_path)), timeout_(timeout) {}

std::string SimControl::request(const std::string& line) {
    UnixSocket socket = UnixSocket::connect(path_, "sim control " + path_, timeout_);
    socket.send_all(line + "\n", timeout_);
    auto reply = socket.read_line(timeout_);
    if (!reply) throw std::runtime_error("sim control: no answer to '" + line + "'");
    const auto json = nlohmann::json::parse(*reply, nullptr, false);
    if (json.is_discarded() || !json.is_object())
        throw std::runtime_error("sim control: malformed answer to '" + line + "': " + *reply);
    if (!json.value("ok", false))
        throw std::runtime_error("sim control: " + line + ": " + json.value("error", *reply));
    return *reply;
}

}  // namespace tilejet::drivers::sim
