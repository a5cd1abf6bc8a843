#include "unix_socket.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/uio.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <thread>
#include <utility>

namespace tilejet::drivers::sim {

namespace {

sockaddr_un address(const std::string& path) {
    sockaddr_un a{};
    a.sun_family = AF_UNIX;
    if (path.size() >= sizeof(a.sun_path))
        throw std::runtime_error("socket path too long (max " +
                                 std::to_string(sizeof(a.sun_path) - 1) + " bytes): " + path);
    std::memcpy(a.sun_path, path.c_str(), path.size() + 1);
    return a;
}

std::string error_text(const std::string& what, const std::string& doing) {
    return what + ": " + doing + ": " + std::strerror(errno);
}

}  // namespace

UnixSocket::~UnixSocket() {
    if (fd_ >= 0) ::close(fd_);
}

UnixSocket::UnixSocket(UnixSocket&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)),
      what_(std::move(other.what_)),
      buffer_(std::move(other.buffer_)) {}

UnixSocket& UnixSocket::operator=(UnixSocket&& other) noexcept {
    if (this != &other) {
        if (fd_ >= 0) ::close(fd_);
        fd_ = std::exchange(other.fd_, -1);
        what_ = std::move(other.what_);
        buffer_ = std::move(other.buffer_);
    }
    return *this;
}

UnixSocket UnixSocket::connect(const std::string& path, const std::string& what,
                               std::chrono::milliseconds timeout) {
    const sockaddr_un a = address(path);
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    // Retried until the deadline: the simulator may still be creating its socket.
    while (true) {
        UnixSocket s(::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0));
        s.what_ = what;
        if (s.fd_ < 0) throw std::runtime_error(error_text(what, "socket"));
        if (::connect(s.fd_, reinterpret_cast<const sockaddr*>(&a), sizeof a) == 0) return s;
        if ((errno != ENOENT && errno != ECONNREFUSED) ||
            std::chrono::steady_clock::now() >= deadline)
            throw std::runtime_error(error_text(what, "cannot connect to " + path));
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
}

void UnixSocket::send_all(std::string_view bytes, std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (!bytes.empty()) {
        const ssize_t n = ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
        if (n > 0) {
            bytes.remove_prefix(size_t(n));
            continue;
        }
        if (n < 0 && errno != EAGAIN && errno != EINTR)
            throw std::runtime_error(error_text(what_, "send"));
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
            deadline - std::chrono::steady_clock::now());
        if (left.count() <= 0) throw std::runtime_error(what_ + ": send timed out");
        pollfd p{fd_, POLLOUT, 0};
        ::poll(&p, 1, int(left.count()) + 1);
    }
}

void UnixSocket::send_with_fd(std::string_view bytes, int fd, std::chrono::milliseconds timeout) {
    iovec v{const_cast<char*>(bytes.data()), bytes.size()};
    alignas(cmsghdr) char control[CMSG_SPACE(sizeof(int))] = {};
    msghdr m{};
    m.msg_iov = &v;
    m.msg_iovlen = 1;
    m.msg_control = control;
    m.msg_controllen = sizeof control;
    cmsghdr* c = CMSG_FIRSTHDR(&m);
    c->cmsg_level = SOL_SOCKET;
    c->cmsg_type = SCM_RIGHTS;
    c->cmsg_len = CMSG_LEN(sizeof(int));
    std::memcpy(CMSG_DATA(c), &fd, sizeof fd);
    const ssize_t n = ::sendmsg(fd_, &m, MSG_NOSIGNAL);
    if (n < 0) throw std::runtime_error(error_text(what_, "sendmsg"));
    send_all(bytes.substr(size_t(n)), timeout);  // the descriptor went with the first byte
}

std::optional<std::string> UnixSocket::read_line(std::chrono::microseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (true) {
        if (const size_t nl = buffer_.find('\n'); nl != std::string::npos) {
            std::string line = buffer_.substr(0, nl);
            buffer_.erase(0, nl + 1);
            return line;
        }
        const auto left = std::chrono::duration_cast<std::chrono::microseconds>(
            deadline - std::chrono::steady_clock::now());
        pollfd p{fd_, POLLIN, 0};
        // poll has millisecond resolution; round up so a short timeout still waits.
        const int ms = left.count() <= 0 ? 0 : int((left.count() + 999) / 1000);
        const int rc = ::poll(&p, 1, ms);
        if (rc < 0 && errno != EINTR) throw std::runtime_error(error_text(what_, "poll"));
        if (rc <= 0) {
            if (std::chrono::steady_clock::now() >= deadline) return std::nullopt;
            continue;
        }
        char chunk[4096];
        const ssize_t n = ::recv(fd_, chunk, sizeof chunk, MSG_DONTWAIT);
        if (n == 0) throw std::runtime_error(what_ + ": the simulator closed the connection");
        if (n < 0) {
            if (errno == EAGAIN || errno == EINTR) continue;
            throw std::runtime_error(error_text(what_, "recv"));
        }
        buffer_.append(chunk, size_t(n));
    }
}

namespace {

// The folder of the simulator's sockets is private: whoever can write there can fake the
// e-stop line or the heads. Made 0700 when missing; refused when it is a symlink, another
// user's, or not a folder; tightened to 0700 when it is ours.
void make_private_folder(const std::filesystem::path& dir) {
    std::error_code ignored;
    std::filesystem::create_directories(dir.parent_path(), ignored);
    if (::mkdir(dir.c_str(), 0700) != 0 && errno != EEXIST)
        throw std::runtime_error(error_text(dir.string(), "cannot make the socket folder"));
    struct stat st {};
    if (::lstat(dir.c_str(), &st) != 0)
        throw std::runtime_error(error_text(dir.string(), "cannot check the socket folder"));
    if (!S_ISDIR(st.st_mode))
        throw std::runtime_error("simulator socket folder " + dir.string() +
                                 " is not a folder (a symlink?): refusing to use it");
    if (st.st_uid != ::geteuid())
        throw std::runtime_error("simulator socket folder " + dir.string() +
                                 " belongs to another user: refusing to use it");
    if ((st.st_mode & 077) != 0 && ::chmod(dir.c_str(), 0700) != 0)
        throw std::runtime_error(error_text(dir.string(), "cannot make the socket folder private"));
}

}  // namespace

int listen_unix(const std::string& path) {
    const sockaddr_un a = address(path);
    make_private_folder(std::filesystem::path(path).parent_path());
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
    const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
    if (fd < 0) throw std::runtime_error(error_text(path, "socket"));
    if (::bind(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0 || ::listen(fd, 16) != 0) {
        const std::string message = error_text(path, "cannot listen");
        ::close(fd);
        throw std::runtime_error(message);
    }
    return fd;
}

}  // namespace tilejet::drivers::sim
