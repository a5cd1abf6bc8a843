#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <string_view>

// A connected Unix stream socket carrying the simulator's line protocols (sim GPIO chip, heads,
// control). Every operation takes a timeout: a simulator that hangs must not hang tilejet.
namespace tilejet::drivers::sim {

class UnixSocket {
  public:
    UnixSocket() = default;
    explicit UnixSocket(int fd) : fd_(fd) {}
    ~UnixSocket();
    UnixSocket(UnixSocket&& other) noexcept;
    UnixSocket& operator=(UnixSocket&& other) noexcept;

    // Connects to `path`; `what` names the peer in errors ("sim gpio chip").
    static UnixSocket connect(const std::string& path, const std::string& what,
                              std::chrono::milliseconds timeout);

    void send_all(std::string_view bytes, std::chrono::milliseconds timeout);
    // `bytes` with a copy of file descriptor `fd` attached (SCM_RIGHTS); the caller keeps `fd`.
    void send_with_fd(std::string_view bytes, int fd, std::chrono::milliseconds timeout);
    // The next '\n'-terminated line (without the '\n'), or nothing if `timeout` passes first.
    // Throws when the peer closed the socket.
    std::optional<std::string> read_line(std::chrono::microseconds timeout);
    int fd() const { return fd_; }
    const std::string& what() const { return what_; }

  private:
    int fd_ = -1;
    std::string what_;
    std::string buffer_;
};

// A listening Unix socket at `path`, replacing a stale socket file left by a killed process.
int listen_unix(const std::string& path);

}  // namespace tilejet::drivers::sim
