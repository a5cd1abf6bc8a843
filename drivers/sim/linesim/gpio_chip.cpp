#include "gpio_chip.hpp"

#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <sstream>

#include "../unix_socket.hpp"

namespace tilejet::linesim {

using drivers::GpioInput;
using drivers::GpioOutput;

GpioChip::GpioChip(std::string path) : path_(std::move(path)) {
    listen_fd_ = drivers::sim::listen_unix(path_);
}

GpioChip::~GpioChip() {
    for (const Peer& p : peers_)
        ::close(p.fd);
    ::close(listen_fd_);
    ::unlink(path_.c_str());
}

std::vector<int> GpioChip::fds() const {
    std::vector<int> fds{listen_fd_};
    for (const Peer& p : peers_)
        fds.push_back(p.fd);
    return fds;
}

void GpioChip::broadcast(const std::string& line) {
    for (const Peer& p : peers_)
        p.send(line);
}

void GpioChip::on_readable(int fd) {
    if (fd == listen_fd_) {
        const int client = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
        if (client < 0) return;
        Peer peer{client, {}};
        std::string greeting;
        for (GpioInput i : drivers::kGpioInputs)
            greeting += "LEVEL " + std::string(drivers::config_key(i)) + " " +
                        (inputs_[size_t(i)] ? "1" : "0") + " 0\n";
        peer.send(greeting + "READY\n");
        peers_.push_back(std::move(peer));
        return;
    }
    auto it =
        std::find_if(peers_.begin(), peers_.end(), [fd](const Peer& p) { return p.fd == fd; });
    if (it == peers_.end()) return;
    const bool open = it->fill();
    std::string line;
    while (it->next_line(line)) {
        std::istringstream in(line);
        std::string verb, name;
        int level = -1;
        in >> verb >> name >> level;
        bool known = false;
        for (GpioOutput o : drivers::kGpioOutputs)
            if (verb == "SET" && name == drivers::config_key(o) && (level == 0 || level == 1)) {
                outputs_[size_t(o)] = level == 1;
                known = true;
            }
        if (!known) it->send("ERROR unknown request '" + line + "'\n");
    }
    if (!open) {
        ::close(it->fd);
        peers_.erase(it);
        // A controller that went away cannot hold the heads enabled.
        if (peers_.empty()) outputs_[size_t(GpioOutput::print_enable)] = false;
    }
}

void GpioChip::set_input(GpioInput input, bool level, ns at) {
    if (inputs_[size_t(input)] == level) return;
    inputs_[size_t(input)] = level;
    broadcast("EDGE " + std::string(drivers::config_key(input)) + (level ? " 1 " : " 0 ") +
              std::to_string(at.count()) + "\n");
}

void GpioChip::glitch(GpioInput input, ns at, ns width) {
    const std::string name(drivers::config_key(input));
    const bool level = inputs_[size_t(input)];
    broadcast("EDGE " + name + (level ? " 0 " : " 1 ") + std::to_string(at.count()) + "\n" +
              "EDGE " + name + (level ? " 1 " : " 0 ") + std::to_string((at + width).count()) +
              "\n");
}

}  // namespace tilejet::linesim
