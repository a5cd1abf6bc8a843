// tilejetd as a systemd service without systemd: the unit file checked by systemd-analyze, and
// the sd_notify protocol (READY, STATUS, WATCHDOG, STOPPING) read off a notify socket of the
// test's own, as systemd would receive it.
#include <sys/socket.h>
#include <sys/un.h>

#include <catch2/catch.hpp>
#include <cstdio>
#include <cstdlib>

#include "daemon_process.hpp"

using namespace tilejet;
using namespace std::chrono_literals;

namespace {

std::string run_command(const std::string& command, int& status) {
    std::string out;
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    if (!pipe) throw std::runtime_error("cannot run " + command);
    char buffer[512];
    while (std::fgets(buffer, sizeof buffer, pipe))
        out += buffer;
    status = pclose(pipe);
    return out;
}

// A datagram socket bound where NOTIFY_SOCKET points, as systemd's.
class NotifySocket {
  public:
    explicit NotifySocket(const std::filesystem::path& path) : path_(path.string()) {
        fd_ = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
        sockaddr_un a{};
        a.sun_family = AF_UNIX;
        REQUIRE(path_.size() < sizeof a.sun_path);
        std::snprintf(a.sun_path, sizeof a.sun_path, "%s", path_.c_str());
        REQUIRE(bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0);
    }
    ~NotifySocket() { close(fd_); }

    // Every message that arrives within `window`.
    std::vector<std::string> collect(std::chrono::milliseconds window) {
        std::vector<std::string> messages;
        const auto end = std::chrono::steady_clock::now() + window;
        while (true) {
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                end - std::chrono::steady_clock::now());
            if (left.count() <= 0) break;
            pollfd p{fd_, POLLIN, 0};
            if (poll(&p, 1, int(left.count())) <= 0) continue;
            char buffer[4096];
            const ssize_t n = recv(fd_, buffer, sizeof buffer, 0);
            if (n > 0) messages.emplace_back(buffer, size_t(n));
        }
        return messages;
    }

  private:
    std::string path_;
    int fd_ = -1;
};

int count_with(const std::vector<std::string>& messages, const std::string& text) {
    return int(std::count_if(messages.begin(), messages.end(), [&](const std::string& m) {
        return m.find(text) != std::string::npos;
    }));
}

}  // namespace

TEST_CASE("the systemd unit file passes systemd-analyze verify", "[daemon][systemd]") {
    int status = 0;
    run_command("command -v systemd-analyze", status);
    if (status != 0) {
        WARN("SKIPPED: systemd-analyze is not installed");
        return;
    }
    test::TempDir dir;
    // The installed path of the binary does not exist here: point ExecStart at the built one.
    std::ifstream in(TILEJET_SOURCE_DIR "/config/tilejetd.service");
    std::stringstream unit;
    unit << in.rdbuf();
    std::string text = unit.str();
    const std::string installed = "/usr/local/bin/tilejetd";
    REQUIRE(text.find(installed) != std::string::npos);
    text.replace(text.find(installed), installed.size(), TILEJETD);
    const auto path = dir.path() / "tilejetd.service";
    std::ofstream(path) << text;
    const std::string out = run_command("systemd-analyze verify " + path.string(), status);
    INFO(out);
    CHECK(status == 0);
    CHECK(out.empty());  // systemd-analyze only warns about bad values, so any output counts
}

TEST_CASE("tilejetd speaks sd_notify: READY, STATUS, WATCHDOG while the loop turns, STOPPING",
          "[daemon][systemd]") {
    test::LinesimProcess line;
    test::TempDir dir;
    NotifySocket systemd(dir.path() / "notify.sock");
    // Children inherit the environment: only the daemon started here sees these.
    setenv("NOTIFY_SOCKET", (dir.path() / "notify.sock").c_str(), 1);
    setenv("WATCHDOG_USEC", "400000", 1);
    test::DaemonProcess daemon(line, dir.path());
    unsetenv("NOTIFY_SOCKET");
    unsetenv("WATCHDOG_USEC");

    const auto running = systemd.collect(1500ms);
    REQUIRE_FALSE(running.empty());
    CHECK(running.front().find("READY=1") != std::string::npos);
    CHECK(running.front().find("STATUS=API on 127.0.0.1:" + std::to_string(daemon.port())) !=
          std::string::npos);
    CHECK(count_with(running, "READY=1") == 1);
    // Pinged at half the watchdog interval: about 7 in 1.5 s; 3 leaves room for a loaded host.
    CHECK(count_with(running, "WATCHDOG=1") >= 3);
    CHECK(count_with(running, "STATUS=idle") >= 1);

    daemon.stop(SIGTERM);
    const auto stopping = systemd.collect(300ms);
    CHECK(count_with(stopping, "STOPPING=1") == 1);
}
