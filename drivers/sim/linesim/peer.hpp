#pragma once

#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <string>

// One client of a simulator socket: its fd and the bytes read but not yet used.
namespace tilejet::linesim {

struct Peer {
    int fd = -1;
    std::string in;

    // Reads what is there without blocking; false when the peer closed or failed.
    bool fill() {
        char chunk[65536];
        while (true) {
            const ssize_t n = ::recv(fd, chunk, sizeof chunk, MSG_DONTWAIT);
            if (n > 0) {
                in.append(chunk, size_t(n));
                if (size_t(n) < sizeof chunk) return true;
                continue;
            }
            if (n < 0 && (errno == EAGAIN || errno == EINTR)) return true;
            return false;
        }
    }
    // Best effort: a peer that does not read its replies loses them, the simulator never blocks.
    void send(const std::string& text) const {
        [[maybe_unused]] ssize_t n =
            ::send(fd, text.data(), text.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
    }
    bool next_line(std::string& line) {
        const size_t nl = in.find('\n');
        if (nl == std::string::npos) return false;
        line = in.substr(0, nl);
        in.erase(0, nl + 1);
        return true;
    }
};

}  // namespace tilejet::linesim
