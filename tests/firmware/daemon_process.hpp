#pragma once

// DaemonProcess: tilejetd started as a separate process for one test, against a
// LinesimProcess, with its API on a port the kernel picks and its job store in a private temp
// folder. The destructor always kills and reaps it; kill() is SIGKILL, the crash under test.
// Its config has one user of each role (kTestUsers); request() signs in as the operator.
#include <fcntl.h>
#include <httplib.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "../child_process.hpp"
#include "../drivers/linesim_process.hpp"
#include "tilejet/api/password.hpp"

namespace tilejet::test {

struct TestUser {
    const char* name;
    const char* role;
    const char* password;
};
inline constexpr TestUser kTestUsers[] = {{"olga", "operator", "olga-operator-pw"},
                                          {"erik", "engineer", "erik-engineer-pw"},
                                          {"vera", "viewer", "vera-viewer-pw"}};

// A signed-in client's headers: the session cookie and the CSRF token.
struct SignedIn {
    httplib::Headers headers;
};

struct DaemonOptions {
    int speed_mm_s = 1000;
    int min_speed_mm_s = 100;
    int render_threads = 2;
    int queue_tiles = 6;
};

class DaemonProcess {
  public:
    DaemonProcess(const LinesimProcess& line, const std::filesystem::path& dir,
                  const DaemonOptions& o = {})
        : designs_(dir / "designs"),
          config_path_((dir / "tilejetd.toml").string()),
          log_path_((dir / "tilejetd.log").string()) {
        std::ifstream in(line.config_path());
        std::stringstream cfg;
        cfg << in.rdbuf();
        cfg << "[colour]\noutput_profile = \"" << TILEJET_TEST_CMYK_PROFILE << "\"\n"
            << "[storage]\ndatabase = \"" << (dir / "jobs.db").string() << "\"\n"
            << "previews = \"" << (dir / "previews").string() << "\"\npreview_tiles = 2\n"
            << "designs = \"" << (dir / "designs").string() << "\"\n"
            << "[api]\nport = 0\n"
            << "[render]\nthreads = " << o.render_threads << "\nqueue_tiles = " << o.queue_tiles
            << "\ndpi = 20\n"
            << "[print]\nspeed_mm_s = " << o.speed_mm_s << "\nmin_speed_mm_s = " << o.min_speed_mm_s
            << "\ndrain_timeout_s = 5\n";
        // Few PBKDF2 iterations: every test signs in, and the hash's strength is not under test.
        for (const TestUser& u : kTestUsers)
            cfg << "[[users]]\nname = \"" << u.name << "\"\nrole = \"" << u.role
                << "\"\npassword_hash = \"" << api::hash_password(u.password, 1000) << "\"\n";
        std::ofstream(config_path_) << cfg.str();
        start();
    }
    ~DaemonProcess() { stop(SIGTERM); }

    // Copies a map into the daemon's designs folder (jobs name designs there), unless a file
    // of that name is there already (never under a job that may be loading it), and returns
    // its name there; `as` renames it.
    std::string add_design(const std::filesystem::path& map, const std::string& as = "") const {
        std::filesystem::create_directories(designs_);
        const std::string name = as.empty() ? map.filename().string() : as;
        if (!std::filesystem::exists(designs_ / name))
            std::filesystem::copy_file(map, designs_ / name);
        return name;
    }
    const std::filesystem::path& designs() const { return designs_; }
    DaemonProcess(const DaemonProcess&) = delete;
    DaemonProcess& operator=(const DaemonProcess&) = delete;

    void start() {
        int out[2];
        if (pipe(out) != 0) throw std::runtime_error("pipe failed");
        pid_ = fork();
        if (pid_ < 0) {
            const std::string why = std::strerror(errno);
            close(out[0]);
            close(out[1]);
            throw std::runtime_error("tilejetd not started: fork: " + why);
        }
        if (pid_ == 0) {
            dup2(out[1], STDOUT_FILENO);
            const int log = ::open(log_path_.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
            dup2(log, STDERR_FILENO);
            detach_from_test();
            execl(TILEJETD, TILEJETD, "--config", config_path_.c_str(),
                  static_cast<char*>(nullptr));
            _exit(127);
        }
        close(out[1]);
        std::string text;
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
        while (text.find('\n') == std::string::npos) {
            pollfd p{out[0], POLLIN, 0};
            if (std::chrono::steady_clock::now() > deadline || poll(&p, 1, 200) < 0) break;
            char buffer[256];
            if (p.revents == 0) continue;
            const ssize_t n = read(out[0], buffer, sizeof buffer);
            if (n <= 0) break;
            text.append(buffer, size_t(n));
        }
        close(out[0]);
        if (text.find('\n') == std::string::npos) {
            // Whether it died (and how) or hangs is the first thing to know.
            int status = 0;
            std::string how = "still running after 10 s without its ready line";
            if (waitpid(pid_, &status, WNOHANG) == pid_) {
                how = WIFSIGNALED(status) ? "killed by signal " + std::to_string(WTERMSIG(status))
                                          : "exited with " + std::to_string(WEXITSTATUS(status));
                pid_ = -1;
            }
            stop(SIGKILL);
            throw std::runtime_error("tilejetd did not start (" + how + "; stdout '" + text +
                                     "'); log:\n" + log());
        }
        port_ = nlohmann::json::parse(text.substr(0, text.find('\n'))).at("api_port").get<int>();
    }

    // Signals the daemon and reaps it (SIGKILL after 10 s).
    void stop(int signal) {
        if (pid_ <= 0) return;
        kill(pid_, signal);
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
        while (waitpid(pid_, nullptr, WNOHANG) == 0) {
            if (std::chrono::steady_clock::now() > deadline) {
                kill(pid_, SIGKILL);
                waitpid(pid_, nullptr, 0);
                break;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
        pid_ = -1;
    }

    std::string log() const {
        std::ifstream in(log_path_);
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
    }

    // Signs in as `user` (one of kTestUsers); throws unless the daemon says yes.
    SignedIn sign_in(const std::string& user) const {
        for (const TestUser& u : kTestUsers)
            if (u.name == user) {
                const auto r =
                    client().Post("/api/session",
                                  nlohmann::json{{"user", u.name}, {"password", u.password}}.dump(),
                                  "application/json");
                if (!r || r->status != 200)
                    throw std::runtime_error("sign-in as " + user + " refused");
                const std::string cookie = r->get_header_value("Set-Cookie");
                return {{{"Cookie", cookie.substr(0, cookie.find(';'))},
                         {"X-CSRF-Token", nlohmann::json::parse(r->body).at("csrf")}}};
            }
        throw std::invalid_argument("no test user " + user);
    }

    // One API request as the operator: {status, parsed body (null when not JSON)}.
    std::pair<int, nlohmann::json> request(const std::string& method, const std::string& path,
                                           const std::string& body = {}) const {
        if (!operator_ || operator_port_ != port_) {
            operator_ = sign_in("olga");
            operator_port_ = port_;
        }
        auto answer = request_as(*operator_, method, path, body);
        // A restarted daemon has forgotten the session (same port or not): sign in once more.
        if (answer.first == 401) {
            operator_ = sign_in("olga");
            answer = request_as(*operator_, method, path, body);
        }
        return answer;
    }
    std::pair<int, nlohmann::json> request_as(const SignedIn& who, const std::string& method,
                                              const std::string& path,
                                              const std::string& body = {}) const {
        auto c = client();
        auto r = method == "GET"      ? c.Get(path.c_str(), who.headers)
                 : method == "PUT"    ? c.Put(path.c_str(), who.headers, body, "application/json")
                 : method == "DELETE" ? c.Delete(path.c_str(), who.headers)
                                      : c.Post(path.c_str(), who.headers, body, "application/json");
        if (!r) throw std::runtime_error("tilejetd API not answering on " + path);
        return {r->status, nlohmann::json::parse(r->body, nullptr, false)};
    }

    httplib::Client client() const {
        httplib::Client c("127.0.0.1", port_);
        c.set_connection_timeout(2, 0);
        c.set_read_timeout(10, 0);
        return c;
    }

    nlohmann::json job(std::int64_t id) const {
        return request("GET", "/api/jobs/" + std::to_string(id)).second;
    }

    int port() const { return port_; }
    pid_t pid() const { return pid_; }
    const std::string& config_path() const { return config_path_; }
    // A signal without waiting for the daemon to exit (SIGHUP).
    void signal(int sig) const { kill(pid_, sig); }

  private:
    std::filesystem::path designs_;
    std::string config_path_, log_path_;
    pid_t pid_ = -1;
    int port_ = 0;
    mutable std::optional<SignedIn> operator_;
    mutable int operator_port_ = 0;
};

}  // namespace tilejet::test
