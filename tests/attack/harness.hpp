#pragma once

// The attack suite's target and instruments: tilejet-linesim and tilejetd in a private folder,
// the signed-in users, a monitor that asks GET /api/status as the operator while an attack runs
// and samples the daemon's resident memory, and raw loopback sockets for traffic no HTTP
// client library would send.
#include <httplib.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <functional>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "../firmware/daemon_process.hpp"
#include "tilejet/api/access.hpp"

namespace tilejet::attack {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;
using std::chrono::seconds;

// How hard each attack pushes: the figures in the long form, fewer connections and
// shorter holds in the short one (CTest), the same sizes where size is the point.
struct Scale {
    bool short_form = false;
    int slow_senders = 32;
    seconds slow_hold{20};
    int idle_connections = 300;
    seconds idle_hold{20};
    int event_streams = 300;
    seconds stream_hold{20};
    std::size_t body_blob = std::size_t(200) << 20;
    std::size_t line_blob = std::size_t(300) << 20;
    int guesses = 40;
    int viewer_sign_ins = 64;
    int race_rounds = 8;
    std::size_t upload_blob = std::size_t(200) << 20;
    static Scale short_scale();
};

// One attack's findings: every reason it failed, and figures worth printing beside them.
struct Verdict {
    std::vector<std::string> failures;
    std::vector<std::string> notes;
    void fail(std::string why) { failures.push_back(std::move(why)); }
    void note(std::string what) { notes.push_back(std::move(what)); }
    void expect(bool ok, std::string why) {
        if (!ok) fail(std::move(why));
    }
};

struct Answer {
    int status = -1;  // -1: no answer (refused, reset or timed out)
    nlohmann::json body;
    std::string text;
    std::string error;  // why there was no answer
    double ms = 0;
};

class Target {
  public:
    explicit Target(const fs::path& maps);
    ~Target();
    Target(const Target&) = delete;
    Target& operator=(const Target&) = delete;

    int port() const { return daemon_->port(); }
    pid_t pid() const { return daemon_->pid(); }
    const fs::path& dir() const { return dir_.path(); }
    fs::path designs() const { return dir_.path() / "designs"; }
    const fs::path& maps() const { return maps_; }
    // Set when the daemon was found dead or killed: the next attack starts it again.
    bool alive() const;
    void restart();
    // Kills the daemon before it takes the machine down with it (the safety cap).
    void kill_now() const;
    long rss_kb() const;

    const httplib::Headers& operator_session() const { return operator_; }
    const httplib::Headers& engineer_session() const { return engineer_; }
    const httplib::Headers& viewer_session() const { return viewer_; }
    std::string host_header() const { return "127.0.0.1:" + std::to_string(port()); }

    // Signs in again whoever an earlier attack signed out (a session flood may, and is failed
    // for it), so that the attacks after it measure themselves; says whom in `renewed`.
    void renew_sessions(std::vector<std::string>& renewed);

    Answer request(const httplib::Headers& who, const std::string& method, const std::string& path,
                   const std::string& body = {}, seconds timeout = seconds(10),
                   const char* type = "application/json") const;
    Answer sign_in(const std::string& user, const std::string& password,
                   const httplib::Headers& extra = {}) const;
    httplib::Headers session_of(const std::string& user) const;

    // The job list and print log an attack must leave as they were.
    std::optional<std::string> jobs() const;
    std::string print_log() const;
    // Waits (bounded) until no job is queued or printing, so that the list stands still.
    bool wait_idle(seconds timeout) const;
    // The body of a job printing `design` (in the designs folder) for `tiles` tiles: by name
    // where the daemon takes names, else by its absolute path.
    std::string job_body(const std::string& design, int tiles) const;
    // Bytes of a small valid design (built at 20 dpi) and of another one (at 36 dpi).
    const std::string& design_a() const { return design_a_; }
    const std::string& design_b() const { return design_b_; }

    // Sign-in failures count against 127.0.0.1 for a window: attacks that sign in wait it out
    // after the guessing attack, or they would measure its lock-out instead of themselves.
    void guessed_now() { guessed_at_ = Clock::now(); }
    void wait_sign_in_window() const;

  private:
    void sign_in_all();

    fs::path maps_;
    test::LinesimProcess line_;
    test::TempDir dir_;
    std::unique_ptr<test::DaemonProcess> daemon_;
    httplib::Headers operator_, engineer_, viewer_;
    std::string design_a_, design_b_;
    mutable std::optional<bool> by_name_;
    std::optional<Clock::time_point> guessed_at_;
};

// Asks GET /api/status as the operator every ~200 ms and samples VmRSS every 50 ms from
// construction until stop(); past the safety cap it kills the daemon (recorded, a FAIL).
class Monitor {
  public:
    Monitor(Target& target, long baseline_kb);
    ~Monitor();
    void stop();
    double worst_ms() const { return worst_ms_; }
    double growth_mb() const { return double(peak_kb_ - baseline_kb_) / 1024.0; }
    int unanswered() const { return unanswered_; }
    int refused() const { return refused_; }
    int last_refusal() const { return last_refusal_; }
    bool killed() const { return killed_; }

  private:
    Target& target_;
    long baseline_kb_;
    std::atomic<bool> stop_{false};
    std::atomic<long> peak_kb_;
    std::atomic<double> worst_ms_{0};
    std::atomic<int> unanswered_{0}, refused_{0}, last_refusal_{0};
    std::atomic<bool> killed_{false};
    std::thread status_, memory_;
};

// Raw loopback sockets.
int connect_loopback(int port, milliseconds timeout = milliseconds(1000));
// Sends everything unless the peer closes, answers or stops reading for `stall`: false then.
bool send_bytes(int fd, std::string_view bytes, milliseconds stall = milliseconds(3000));
// What the peer sent so far (or within `wait`), without blocking past it; empty on nothing.
std::string read_some(int fd, milliseconds wait);
int status_of(const std::string& response);  // the code on an HTTP status line, or -1

// A request body (or request line, or header block) streamed at the server in pieces.
struct StreamResult {
    std::size_t sent = 0;
    bool finished = false;  // the whole thing went out: the server read (nearly) all of it
    int status = -1;        // its answer, if any
    std::string how;        // how it ended, in words
};
StreamResult stream_blob(int port, const std::string& head, std::size_t total,
                         const std::function<std::string(std::size_t)>& piece,
                         const std::string& tail);

std::string mib(std::size_t bytes);
std::string read_file(const fs::path& p);

struct Attack {
    const char* name;
    std::function<void(Target&, const Scale&, Verdict&)> run;
};
std::vector<Attack> connection_attacks();
std::vector<Attack> sign_in_attacks();
std::vector<Attack> file_attacks();

}  // namespace tilejet::attack
