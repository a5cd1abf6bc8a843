#pragma once

// SIGPIPE held back for this thread while it writes into a pipe whose reader may be gone: such a
// write raises SIGPIPE, which would end a process that has not ignored it (tilejetd does; a test
// binary may not). A SIGPIPE the write raised (say so with raised()) is taken back on the way
// out, so the failure is an EPIPE error like any other.

#include <pthread.h>
#include <signal.h>

namespace tilejet::drivers::sim {

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
    SigpipeHeld(const SigpipeHeld&) = delete;
    SigpipeHeld& operator=(const SigpipeHeld&) = delete;
    void raised() { raised_ = true; }

  private:
    sigset_t sigpipe_{}, old_{};
    bool was_pending_ = false, raised_ = false;
};

}  // namespace tilejet::drivers::sim
