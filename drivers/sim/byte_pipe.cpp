#include "byte_pipe.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/uio.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "sigpipe_held.hpp"

namespace tilejet::drivers::sim {

namespace {

// Fewer, larger handovers; the default pipe holds 64 KB. Above /proc/sys/fs/pipe-max-size (1 MB
// by default) the kernel refuses, and the default size still works, only slower.
constexpr int kPipeBytes = 1 << 20;

}  // namespace

BytePipe::BytePipe() {
    int ends[2];
    if (::pipe2(ends, O_CLOEXEC) != 0)
        throw std::runtime_error(std::string("sim heads: pipe2: ") + std::strerror(errno));
    read_ = ends[0];
    write_ = ends[1];
    ::fcntl(write_, F_SETPIPE_SZ, kPipeBytes);
}

BytePipe::~BytePipe() {
    close_read_end();
    if (write_ >= 0) ::close(write_);
}

void BytePipe::close_read_end() {
    if (read_ >= 0) ::close(read_);
    read_ = -1;
}

void BytePipe::write_all(std::span<const std::uint8_t> bytes, std::chrono::milliseconds timeout,
                         const std::string& what) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    SigpipeHeld sigpipe;  // vmsplice into a pipe whose reader is gone raises SIGPIPE
    while (!bytes.empty()) {
        iovec v{const_cast<std::uint8_t*>(bytes.data()), bytes.size()};
        const ssize_t n = ::vmsplice(write_, &v, 1, SPLICE_F_NONBLOCK);
        if (n > 0) {
            bytes = bytes.subspan(size_t(n));
            continue;
        }
        if (n < 0 && errno == EPIPE) sigpipe.raised();
        if (n < 0 && errno != EAGAIN && errno != EINTR)
            throw std::runtime_error(what + ": vmsplice: " + std::strerror(errno));
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
            deadline - std::chrono::steady_clock::now());
        if (left.count() <= 0) throw std::runtime_error(what + ": sending separations timed out");
        pollfd p{write_, POLLOUT, 0};
        ::poll(&p, 1, int(left.count()) + 1);
    }
}

}  // namespace tilejet::drivers::sim
