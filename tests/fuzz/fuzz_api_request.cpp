// The whole HTTP API: the daemon's ApiServer on loopback (routing, the gate with its sessions,
// CSRF tokens and roles, sign-in, jobs, line commands, pictures, uploads, the event stream, the
// panel's files), over a backend that answers every call, gets the fuzzer's bytes as what one
// client sends on one TCP connection. Whatever arrives must end in an answer or a closed
// connection, never a crash, a hang or a leak.
//
// So that the bytes can get past the gate into the handlers, the harness can first sign in
// properly (a real POST /api/session, from 127.0.0.2 so that the fuzzer's own failed sign-ins
// from 127.0.0.1 never rate-limit it) and put that session into the bytes: every "$COOKIE"
// becomes the session id (the tilejet_session cookie's value), every "$CSRF" its CSRF token.
// The fuzzer can sign in by itself too: olga (operator), erik (engineer) and vera (viewer),
// passwords "<name>-pw-123", as in tests/firmware/test_api_server.cpp.
//
// Input: byte 0 bits 0-1 = who the harness signs in first (0 nobody, 1 viewer, 2 operator,
// 3 engineer; so "0".."3" in a seed file), bit 2 = read the answer ("4".."7"); the rest = the
// raw bytes, sent on a fresh connection. With bit 2 the harness reads until one whole answer is
// in, the server closes, or nothing comes for 10 ms; then (at once without bit 2) it half-closes,
// and waits for the server to close, at most 200 ms in all (an /api/events stream only ends at
// its next write). One request per input is what counts: the answer read is the first one.
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>

#include "tilejet/api/api_server.hpp"
#include "tilejet/api/password.hpp"

using namespace tilejet;
using nlohmann::json;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

namespace {

// Says yes to everything, so that every handler runs to its end.
class Backend : public api::ApiBackend {
  public:
    // A new status each call: the event hub then publishes every 250 ms, so an event stream
    // whose client went away finds out at its next write instead of after 10 s of quiet.
    json status() override { return {{"state", "printing"}, {"counter", ++counter_}}; }
    json submit(const jobs::JobSpec& spec) override {
        jobs::Job job;
        job.id = 1;
        job.spec = spec;
        return api::job_json(job);
    }
    json jobs() override { return json::array({api::job_json(sample_job(1))}); }
    std::optional<json> job(std::int64_t id) override {
        if (id != 1) return std::nullopt;
        return api::job_json(sample_job(id));
    }
    json command(std::string_view name) override { return {{"accepted", std::string(name)}}; }
    int default_dpi() const override { return 100; }
    std::string tile_png(std::int64_t, std::int64_t, int) override { return png(); }
    std::string wall_png(int, int) override { return png(); }
    json designs() override { return json::array({{{"name", "a.tjmap"}, {"path", "/a.tjmap"}}}); }
    json profiles() override { return json::array({{{"name", "l.icc"}, {"path", "/l.icc"}}}); }
    json add_design(const std::string& name, const std::string& bytes) override {
        return {{"name", name}, {"bytes", bytes.size()}};
    }
    json add_profile(const std::string& name, const std::string& bytes) override {
        return {{"name", name}, {"bytes", bytes.size()}};
    }
    json reload_config() override { return {{"reload", "requested"}}; }

  private:
    static jobs::Job sample_job(std::int64_t id) {
        jobs::Job j;
        j.id = id;
        j.spec = {"/a.tjmap", "", 7, 50, 300, 300, 100, "wall", 4};
        j.status = jobs::JobStatus::printing;
        return j;
    }
    static std::string png() { return std::string("\x89PNG\r\n\x1a\n", 8); }
    std::atomic<std::int64_t> counter_{0};
};

api::AccessSettings access() {
    api::AccessSettings a;
    // One PBKDF2 iteration: a sign-in costs next to nothing (production hashes use 600 000).
    a.users = {{"olga", api::Role::operator_, api::hash_password("olga-pw-123", 1)},
               {"erik", api::Role::engineer, api::hash_password("erik-pw-123", 1)},
               {"vera", api::Role::viewer, api::hash_password("vera-pw-123", 1)},
               {"harness-viewer", api::Role::viewer, api::hash_password("harness-pw", 1)},
               {"harness-operator", api::Role::operator_, api::hash_password("harness-pw", 1)},
               {"harness-engineer", api::Role::engineer, api::hash_password("harness-pw", 1)}};
    // The shortest window: the fuzzer reaches the 429s, and they are over a second later.
    a.sign_in.window = std::chrono::seconds(1);
    return a;
}

// Nonblocking, connected to 127.0.0.1:port from `source` (any when null); -1 when it fails.
int connect_to(int port, const char* source) {
    const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) return -1;
    sockaddr_in a{};
    a.sin_family = AF_INET;
    if (source && inet_pton(AF_INET, source, &a.sin_addr) == 1)
        bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);  // failing: any address will do
    a.sin_port = htons(std::uint16_t(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
        close(fd);
        return -1;
    }
    fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
    return fd;
}

int ms_left(Clock::time_point deadline) {
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - Clock::now());
    return left.count() > 0 ? int(left.count()) : 0;
}

// Sends all of `bytes`; false when the deadline passes or the server is gone.
bool send_all(int fd, const std::string& bytes, Clock::time_point deadline) {
    size_t sent = 0;
    while (sent < bytes.size()) {
        pollfd p{fd, POLLOUT, 0};
        if (poll(&p, 1, ms_left(deadline)) <= 0) return false;
        const ssize_t n = send(fd, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
        if (n <= 0) return false;
        sent += size_t(n);
    }
    return true;
}

// The length of the first whole answer in `reply` (head and Content-Length body); 0 while it
// is not all there, or has no length (an event stream, the answer to a HEAD).
size_t answer_length(const std::string& reply) {
    const size_t head = reply.find("\r\n\r\n");
    const std::string key = "\r\nContent-Length: ";
    const size_t at = reply.find(key);
    if (head == std::string::npos || at == std::string::npos || at > head) return 0;
    const size_t length = std::strtoull(reply.c_str() + at + key.size(), nullptr, 10);
    return reply.size() - head - 4 >= length ? head + 4 + length : 0;
}

struct Reply {
    std::string bytes;
    bool closed = false;  // the server closed the connection
};

// What the server sends until it closes or the deadline passes; with `one_answer`, also until
// a whole answer is in or nothing more comes for `quiet`.
Reply receive(int fd, Clock::time_point deadline, bool one_answer,
              std::chrono::milliseconds quiet = 10ms) {
    Reply r;
    char buffer[16384];
    while (!one_answer || answer_length(r.bytes) == 0) {
        pollfd p{fd, POLLIN, 0};
        const int wait =
            one_answer ? std::min(ms_left(deadline), int(quiet.count())) : ms_left(deadline);
        if (poll(&p, 1, wait) <= 0) break;
        const ssize_t n = recv(fd, buffer, sizeof buffer, 0);
        if (n <= 0) {
            r.closed = true;
            break;
        }
        if (r.bytes.size() < (1 << 20)) r.bytes.append(buffer, size_t(n));
    }
    return r;
}

struct Credentials {
    std::string cookie, csrf;
};

// A real sign-in; nullopt when it is refused (the fuzzer may have rate-limited the user).
std::optional<Credentials> sign_in(int port, const char* user) {
    const std::string body = json{{"user", user}, {"password", "harness-pw"}}.dump();
    const std::string request =
        "POST /api/session HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n"
        "Connection: close\r\nContent-Length: " +
        std::to_string(body.size()) + "\r\n\r\n" + body;
    const int fd = connect_to(port, "127.0.0.2");
    if (fd < 0) return std::nullopt;
    const auto deadline = Clock::now() + 2s;
    std::string reply;
    if (send_all(fd, request, deadline)) reply = receive(fd, deadline, true, 2s).bytes;
    close(fd);
    const std::string set_cookie = "\r\nSet-Cookie: tilejet_session=";
    const size_t at = reply.find(set_cookie);
    const size_t end_of_head = reply.find("\r\n\r\n");
    if (!reply.starts_with("HTTP/1.1 200") || at == std::string::npos ||
        end_of_head == std::string::npos)
        return std::nullopt;
    const size_t value = at + set_cookie.size();
    Credentials c{reply.substr(value, reply.find(';', value) - value), ""};
    const json j = json::parse(reply.substr(end_of_head + 4), nullptr, false);
    if (!j.is_object() || !j.contains("csrf") || !j["csrf"].is_string()) return std::nullopt;
    c.csrf = j["csrf"].get<std::string>();
    return c;
}

void replace_all(std::string& text, const std::string& from, const std::string& to) {
    for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
        text.replace(at, from.size(), to);
}

struct Fixture {
    Backend backend;
    api::ApiServer server{backend, "127.0.0.1", 0, access()};
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static Fixture fixture;
    const int port = fixture.server.port();
    if (size < 1) return 0;
    std::string request(reinterpret_cast<const char*>(data + 1), size - 1);
    static const char* const users[] = {nullptr, "harness-viewer", "harness-operator",
                                        "harness-engineer"};
    if (const char* user = users[data[0] & 3]) {
        if (const auto c = sign_in(port, user)) {
            replace_all(request, "$COOKIE", c->cookie);
            replace_all(request, "$CSRF", c->csrf);
        }
    }
    const int fd = connect_to(port, nullptr);
    if (fd < 0) return 0;
    const auto deadline = Clock::now() + 200ms;
    if (send_all(fd, request, deadline)) {
        // cpp-httplib takes a half-closed connection for a closed one: it still reads what came
        // and runs the handler, but writes nothing. So the answer, when wanted, comes first.
        const bool closed = (data[0] & 4) && receive(fd, deadline, true).closed;
        if (!closed) {
            shutdown(fd, SHUT_WR);
            // The server sees the end, finishes the request and closes: its work is this input's.
            receive(fd, deadline, false);
        }
    }
    close(fd);
    return 0;
}
