#include "byte_pipe.hpp"

#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <sys/uio.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace tilejet::drivers::sim {

namespace {

// Fewer, larger handovers; the default pipe holds 64 KB. Above /proc/sys/fs/pipe-max-size (1 MB
// by default) the kernel refuses, and the default size still works, only slower.
constexpr int kPipeBytes = 1 << 20;

// vmsplice into a pipe whose reader is gone raises SIGPIPE, which would end a process that has
// not ignored it (tilejetd does; a test binary may not). Blocked while writing, and a SIGPIPE
// this write raised is taken back, so the failure is an EPIPE error like any other.
class SigpipeHeld {
  public:
    SigpipeHeld() {
        sigemptyset(&sigpipe_);
        sigaddset(&sigpipe_, SIGPIPE);
        sigset_t pending;
        sigpending(&pending);
        was_pending_ = sigismember(&pending, SIGPIPE) == 1;
        pthread_sigmask(SIG_BLOCK, &sigpipe_, &old_);
    }
    ~SigpipeHeld() {
        if (raised_ && !was_pending_) {
            const timespec now{0, 0};
            sigtimedwait(&sigpipe_, nullptr, &now);
        }
        pthread_sigmask(SIG_SETMASK, &old_, nullptr);
    }
    void raised() { raised_ = true; }

  private:
    sigset_t sigpipe_{}, old_{};
    bool was_pending_ = false, raised_ = false;
};

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
    SigpipeHeld sigpipe;
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
