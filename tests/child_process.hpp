#pragma once

// What a test's helper process (tilejet-linesim, tilejetd) does between fork() and exec(), once
// its own stdout and stderr are in place: it dies with the test, and it holds none of the test's
// other descriptors. A test killed by a signal (SIGPIPE on a write to heads that had closed
// their pipe) left its simulator running, holding CTest's output pipe: CTest waited for that
// pipe to close until its 900 s timeout, and the clean-clone run with it.

#include <signal.h>
#include <sys/prctl.h>
#include <unistd.h>

namespace tilejet::test {

inline void detach_from_test() {
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    // The test's parent may be gone already (it died before the prctl): then so should we.
    if (::getppid() == 1) _exit(126);
    ::close_range(3, ~0U, 0);
}

}  // namespace tilejet::test
