// libFuzzer: the whole daemon config file (all sections, as tilejetd reads it at start).
#include <sys/mman.h>
#include <toml++/toml.h>
#include <unistd.h>

#include <cstdint>
#include <stdexcept>
#include <string>

#include "daemon_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    // The loader takes a path: an in-memory file keeps the disk out of the loop.
    const int fd = memfd_create("tilejet.toml", 0);
    if (fd < 0) return 0;
    if (write(fd, data, size) == ssize_t(size)) {
        try {
            tilejet::daemon::load_daemon_config("/proc/self/fd/" + std::to_string(fd));
        } catch (const toml::parse_error&) {
        } catch (const std::runtime_error&) {  // config errors name file, section and key
        }
    }
    close(fd);
    return 0;
}
