#include "harness.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>

#include <cstdio>
#include <fstream>
#include <sstream>

namespace tilejet::attack {

namespace {

// Far above any honest figure and far below what would take the shared machine down: a daemon
// reading /dev/zero grows by gigabytes a second.
constexpr long kSafetyCapKb = 1536L * 1024;

double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

Scale Scale::short_scale() {
    Scale s;
    s.short_form = true;
    // Twice the API's 16 threads, as in the long form: fewer would measure nothing.
    s.slow_senders = 32;
    s.slow_hold = seconds(5);
    s.idle_connections = 300;
    s.idle_hold = seconds(3);
    s.event_streams = 300;
    s.stream_hold = seconds(3);
    s.guesses = 40;
    s.viewer_sign_ins = 64;
    s.race_rounds = 3;
    return s;
}

std::string mib(std::size_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f MiB", double(bytes) / (1 << 20));
    return text;
}

std::string read_file(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

Target::Target(const fs::path& maps)
    : maps_(maps),
      line_(test::LinesimOptions{}),
      design_a_(read_file(maps / "small.tjmap")),
      design_b_(read_file(maps / "small-36.tjmap")) {
    if (design_a_.empty() || design_b_.empty())
        throw std::runtime_error("no test maps in " + maps.string());
    fs::create_directories(designs());
    daemon_ = std::make_unique<test::DaemonProcess>(line_, dir_.path());
    sign_in_all();
}

Target::~Target() = default;

void Target::sign_in_all() {
    operator_ = session_of("olga");
    engineer_ = session_of("erik");
    viewer_ = session_of("vera");
}

void Target::renew_sessions(std::vector<std::string>& renewed) {
    for (auto [user, session] : {std::pair{"olga", &operator_}, std::pair{"erik", &engineer_},
                                 std::pair{"vera", &viewer_}})
        if (request(*session, "GET", "/api/session").status == 401) {
            *session = session_of(user);
            renewed.push_back(user);
        }
}

bool Target::alive() const {
    // Not reaped here: DaemonProcess reaps its child; a zombie is a dead daemon.
    std::ifstream stat("/proc/" + std::to_string(pid()) + "/stat");
    std::string text;
    std::getline(stat, text);
    const auto close = text.rfind(')');
    return pid() > 0 && close != std::string::npos && close + 2 < text.size() &&
           text[close + 2] != 'Z' && text[close + 2] != 'X';
}

void Target::restart() {
    daemon_->stop(SIGKILL);
    daemon_->start();
    sign_in_all();
}

void Target::kill_now() const {
    if (pid() > 0) ::kill(pid(), SIGKILL);
}

long Target::rss_kb() const {
    std::ifstream status("/proc/" + std::to_string(pid()) + "/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("VmRSS:", 0) == 0) return std::atol(line.c_str() + 6);
    return 0;
}

Answer Target::request(const httplib::Headers& who, const std::string& method,
                       const std::string& path, const std::string& body, seconds timeout,
                       const char* type) const {
    httplib::Client c("127.0.0.1", port());
    c.set_connection_timeout(timeout);
    c.set_read_timeout(timeout);
    c.set_write_timeout(timeout);
    const auto start = Clock::now();
    auto r = method == "GET"      ? c.Get(path.c_str(), who)
             : method == "PUT"    ? c.Put(path.c_str(), who, body, type)
             : method == "DELETE" ? c.Delete(path.c_str(), who)
                                  : c.Post(path.c_str(), who, body, type);
    Answer a;
    a.ms = ms_since(start);
    if (!r) {
        a.error = httplib::to_string(r.error());
        return a;
    }
    a.status = r->status;
    a.text = r->body;
    a.body = nlohmann::json::parse(r->body, nullptr, false);
    return a;
}

Answer Target::sign_in(const std::string& user, const std::string& password,
                       const httplib::Headers& extra) const {
    return request(extra, "POST", "/api/session",
                   nlohmann::json{{"user", user}, {"password", password}}.dump());
}

httplib::Headers Target::session_of(const std::string& user) const {
    for (const test::TestUser& u : test::kTestUsers)
        if (u.name == user) {
            httplib::Client c("127.0.0.1", port());
            c.set_read_timeout(10, 0);
            const auto r = c.Post("/api/session",
                                  nlohmann::json{{"user", u.name}, {"password", u.password}}.dump(),
                                  "application/json");
            if (!r || r->status != 200)
                throw std::runtime_error("sign-in as " + user + " refused (" +
                                         (r ? std::to_string(r->status) : "no answer") + ")");
            const std::string cookie = r->get_header_value("Set-Cookie");
            return {{"Cookie", cookie.substr(0, cookie.find(';'))},
                    {"X-CSRF-Token", nlohmann::json::parse(r->body).at("csrf")}};
        }
    throw std::invalid_argument("no test user " + user);
}

std::optional<std::string> Target::jobs() const {
    const Answer a = request(operator_, "GET", "/api/jobs");
    if (a.status != 200) return std::nullopt;
    return a.text;
}

std::string Target::print_log() const {
    return read_file(line_.print_log_path());
}

bool Target::wait_idle(seconds timeout) const {
    return test::eventually(
        [&] {
            const Answer a = request(operator_, "GET", "/api/jobs", {}, seconds(2));
            if (a.status != 200 || !a.body.is_array()) return false;
            for (const auto& job : a.body)
                if (job.value("status", "") == "queued" || job.value("status", "") == "printing")
                    return false;
            return true;
        },
        timeout);
}

std::string Target::job_body(const std::string& design, int tiles) const {
    auto body = [&](const std::string& map) {
        return nlohmann::json{
            {"map", map}, {"seed", 4242}, {"tiles", tiles}, {"tile_mm", "200x200"}, {"dpi", 20}}
            .dump();
    };
    if (!by_name_) {
        // Asked once by validating a name: a daemon that wants paths says so about "map".
        const Answer a = request(operator_, "POST", "/api/jobs", body("no-such-design.tjmap"));
        by_name_ = !(a.status == 400 && a.body.is_object() && a.body.value("field", "") == "map" &&
                     a.text.find("absolute") != std::string::npos);
    }
    return body(*by_name_ ? design : (designs() / design).string());
}

void Target::wait_sign_in_window() const {
    if (!guessed_at_) return;
    const auto until = *guessed_at_ + api::SignInLimits{}.window + seconds(1);
    if (Clock::now() < until) std::this_thread::sleep_until(until);
}

Monitor::Monitor(Target& target, long baseline_kb)
    : target_(target), baseline_kb_(baseline_kb), peak_kb_(baseline_kb) {
    const httplib::Headers who = target.operator_session();
    const int port = target.port();
    status_ = std::thread([this, who, port] {
        while (!stop_) {
            httplib::Client c("127.0.0.1", port);
            // Past 3 s an answer is long late; waiting longer would only slow the sampling.
            c.set_connection_timeout(3, 0);
            c.set_read_timeout(3, 0);
            const auto start = Clock::now();
            const auto r = c.Get("/api/status", who);
            const double ms = ms_since(start);
            if (ms > worst_ms_) worst_ms_ = ms;
            if (!r) {
                ++unanswered_;
            } else if (r->status != 200) {
                ++refused_;
                last_refusal_ = r->status;
            }
            std::this_thread::sleep_until(start + milliseconds(200));
        }
    });
    const pid_t pid = target.pid();
    memory_ = std::thread([this, pid] {
        while (!stop_) {
            std::ifstream status("/proc/" + std::to_string(pid) + "/status");
            std::string line;
            while (std::getline(status, line))
                if (line.rfind("VmRSS:", 0) == 0) {
                    const long kb = std::atol(line.c_str() + 6);
                    if (kb > peak_kb_) peak_kb_ = kb;
                    if (kb - baseline_kb_ > kSafetyCapKb && !killed_) {
                        ::kill(pid, SIGKILL);
                        killed_ = true;
                    }
                }
            std::this_thread::sleep_for(milliseconds(50));
        }
    });
}

Monitor::~Monitor() {
    stop();
}

void Monitor::stop() {
    stop_ = true;
    if (status_.joinable()) status_.join();
    if (memory_.joinable()) memory_.join();
}

int connect_loopback(int port, milliseconds timeout) {
    const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0) return -1;
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(std::uint16_t(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 && errno != EINPROGRESS) {
        ::close(fd);
        return -1;
    }
    pollfd p{fd, POLLOUT, 0};
    int error = 0;
    socklen_t len = sizeof error;
    if (::poll(&p, 1, int(timeout.count())) != 1 ||
        ::getsockopt(fd, SOL_SOCKET, SO_ERROR, &error, &len) != 0 || error != 0) {
        ::close(fd);
        return -1;
    }
    return fd;
}

bool send_bytes(int fd, std::string_view bytes, milliseconds stall) {
    while (!bytes.empty()) {
        pollfd p{fd, POLLOUT | POLLIN, 0};
        if (::poll(&p, 1, int(stall.count())) != 1) return false;
        // An answer or a close before the request is done: the server has refused it.
        if (p.revents & (POLLIN | POLLERR | POLLHUP)) return false;
        const ssize_t n = ::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL);
        if (n < 0 && (errno == EAGAIN || errno == EINTR)) continue;
        if (n <= 0) return false;
        bytes.remove_prefix(std::size_t(n));
    }
    return true;
}

std::string read_some(int fd, milliseconds wait) {
    std::string text;
    const auto deadline = Clock::now() + wait;
    while (true) {
        const auto left = std::chrono::duration_cast<milliseconds>(deadline - Clock::now()).count();
        pollfd p{fd, POLLIN, 0};
        if (::poll(&p, 1, int(std::max<long>(left, 0))) != 1) break;
        char buffer[4096];
        const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
        if (n <= 0) break;
        text.append(buffer, std::size_t(n));
        if (text.find("\r\n") != std::string::npos) break;
    }
    return text;
}

int status_of(const std::string& response) {
    if (response.rfind("HTTP/1.", 0) != 0 || response.size() < 12) return -1;
    return std::atoi(response.c_str() + 9);
}

StreamResult stream_blob(int port, const std::string& head, std::size_t total,
                         const std::function<std::string(std::size_t)>& piece,
                         const std::string& tail) {
    StreamResult r;
    const int fd = connect_loopback(port);
    if (fd < 0) {
        r.how = "connection refused";
        return r;
    }
    bool open = send_bytes(fd, head);
    r.sent = open ? head.size() : 0;
    while (open && r.sent < total) {
        const std::string bytes = piece(r.sent);
        open = send_bytes(fd, bytes);
        if (open) r.sent += bytes.size();
    }
    if (open) open = send_bytes(fd, tail);
    r.finished = open;
    // Whatever the server said, before or after the whole blob: a refusal has a status line.
    const std::string answer = read_some(fd, milliseconds(open ? 5000 : 1000));
    ::close(fd);
    r.status = status_of(answer);
    const std::string said =
        r.status > 0 ? "answered " + std::to_string(r.status) : "closed or went silent";
    r.how =
        (r.finished ? "took all " + mib(r.sent) + ", then " : "stopped at " + mib(r.sent) + ": ") +
        said;
    return r;
}

}  // namespace tilejet::attack
