// What a hostile client can make the API server spend (http_server.hpp), with limits small
// enough to reach in a test: slow and idle connections, oversize request lines, headers and
// bodies (chunked too), floods of sign-ins and event streams. Through each, a signed-in
// operator's GET /api/status is answered at once. The long forms are tilejet-attack's.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "api_fixtures.hpp"

using namespace tilejet;
using namespace std::chrono_literals;
using test::Client;
using test::FakeBackend;
using Clock = std::chrono::steady_clock;

namespace {

// A raw TCP connection to the server, for traffic no well-behaved client sends.
class RawConnection {
  public:
    explicit RawConnection(int port) : fd_(socket(AF_INET, SOCK_STREAM, 0)) {
        REQUIRE(fd_ >= 0);
        sockaddr_in a{};
        a.sin_family = AF_INET;
        a.sin_port = htons(uint16_t(port));
        a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        REQUIRE(connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0);
    }
    ~RawConnection() { close(fd_); }
    RawConnection(const RawConnection&) = delete;
    RawConnection& operator=(const RawConnection&) = delete;

    // False once the server has closed or reset the connection.
    bool send(const std::string& bytes) {
        return ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL) == ssize_t(bytes.size());
    }
    // Whether the server closed the connection within `timeout` (what it sent before is
    // kept in received()).
    bool closed_within(std::chrono::milliseconds timeout) {
        const auto deadline = Clock::now() + timeout;
        while (Clock::now() < deadline) {
            pollfd p{fd_, POLLIN, 0};
            if (poll(&p, 1, 20) <= 0) continue;
            char buf[4096];
            const ssize_t n = recv(fd_, buf, sizeof buf, 0);
            if (n <= 0) return true;
            received_.append(buf, size_t(n));
        }
        return false;
    }
    const std::string& received() const { return received_; }

  private:
    int fd_;
    std::string received_;
};

api::AccessSettings small_limits() {
    api::AccessSettings a = test::access();
    a.limits.connections = 40;
    a.limits.connections_per_address = 20;
    a.limits.header_timeout = 1s;
    a.limits.body_timeout = 2s;
    a.limits.event_streams = 8;
    a.limits.event_streams_per_session = 2;
    return a;
}

// Limits for a flood of wrong sign-ins as olga: never locked out, each password checked against
// a hash of `rounds` (slow, as on a line).
api::AccessSettings sign_in_flood(int rounds) {
    api::AccessSettings a = small_limits();
    a.sign_in.failures_per_address = 1000;
    a.sign_in.failures_per_user = 1000;
    a.users[0].password_hash = api::hash_password("olga-pw-123", rounds);
    return a;
}

// The worst time GET /api/status took over `rounds` tries as the signed-in operator.
std::chrono::milliseconds worst_status(Client& c, const httplib::Headers& h, int rounds = 5) {
    std::chrono::milliseconds worst{0};
    for (int i = 0; i < rounds; ++i) {
        const auto t0 = Clock::now();
        const auto a = c.send("GET", "/api/status", "", h);
        CHECK(a.status == 200);
        worst = std::max(worst,
                         std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - t0));
    }
    return worst;
}

}  // namespace

TEST_CASE("a client that sends its request a byte at a time is closed at the header deadline",
          "[api][limits]") {
    FakeBackend backend;
    api::ApiServer server(backend, "127.0.0.1", 0, small_limits());
    Client operator_client(server.port());
    const auto h = operator_client.session("olga");
    std::vector<std::unique_ptr<RawConnection>> slow;
    for (int i = 0; i < 10; ++i) {
        slow.push_back(std::make_unique<RawConnection>(server.port()));
        REQUIRE(slow.back()->send("G"));
    }
    const std::string rest = "ET /api/status HTTP/1.1\r\nHost: localhost\r\n";
    const auto t0 = Clock::now();
    size_t sent = 0;
    bool all_closed = false;
    // A byte a tenth of a second each: never idle, never done.
    while (Clock::now() - t0 < 3s && !all_closed) {
        all_closed = true;
        for (auto& c : slow)
            all_closed &= !c->send(rest.substr(sent % rest.size(), 1));
        ++sent;
        CHECK(worst_status(operator_client, h, 1) < 500ms);
        std::this_thread::sleep_for(100ms);
    }
    // Closed at 1 s (the deadline) plus the housekeeper's turn, not at the 3 s the test waits.
    CHECK(all_closed);
    CHECK(Clock::now() - t0 < 2500ms);
}

TEST_CASE("idle connections past the per-address cap make room: the oldest idle one goes",
          "[api][limits]") {
    FakeBackend backend;
    api::ApiServer server(backend, "127.0.0.1", 0, small_limits());
    Client operator_client(server.port());
    const auto h = operator_client.session("olga");
    // The panel's keep-alive connection, between two good answers.
    RawConnection panel(server.port());
    const std::string status_request =
        "GET /api/status HTTP/1.1\r\nHost: localhost\r\nCookie: " + h.find("Cookie")->second +
        "\r\n\r\n";
    REQUIRE(panel.send(status_request));
    CHECK_FALSE(panel.closed_within(300ms));
    REQUIRE_THAT(panel.received(), Catch::StartsWith("HTTP/1.1 200"));
    std::vector<std::unique_ptr<RawConnection>> idle;
    for (int i = 0; i < 30; ++i)  // 20 per address
        idle.push_back(std::make_unique<RawConnection>(server.port()));
    // Every one of the 30 was let in, the oldest closed to make room for the newest...
    int closed = 0;
    for (int i = 0; i < 10; ++i)
        closed += idle[size_t(i)]->closed_within(300ms);
    CHECK(closed == 10);
    CHECK_FALSE(idle.back()->closed_within(100ms));
    // ...and the operator, from the same address, is answered at once, on a new connection and
    // on the panel's: the idle ones went first.
    CHECK(worst_status(operator_client, h) < 500ms);
    REQUIRE(panel.send(status_request));
    CHECK_FALSE(panel.closed_within(300ms));
    CHECK(panel.received().find("HTTP/1.1 200", 10) != std::string::npos);
}

TEST_CASE("request lines and header blocks past 32 KB are refused without being kept",
          "[api][limits]") {
    FakeBackend backend;
    api::ApiServer server(backend, "127.0.0.1", 0, small_limits());
    {
        RawConnection c(server.port());
        c.send(std::string("GET /").append(40000, 'a'));
        c.send(" HTTP/1.1\r\nHost: localhost\r\n\r\n");
        CHECK(c.closed_within(2s));
        CHECK_THAT(c.received(), Catch::StartsWith("HTTP/1.1 414"));
    }
    {
        RawConnection c(server.port());
        c.send(std::string("GET /api/status HTTP/1.1\r\nHost: localhost\r\nX-Filler: ")
                   .append(40000, 'a'));
        c.send("\r\n\r\n");
        CHECK(c.closed_within(2s));
        CHECK_THAT(c.received(), Catch::StartsWith("HTTP/1.1 431"));
    }
}

TEST_CASE("a chunked body past its route's limit is refused as it arrives", "[api][limits]") {
    FakeBackend backend;
    api::ApiServer server(backend, "127.0.0.1", 0, small_limits());
    const std::string head =
        "POST /api/session HTTP/1.1\r\nHost: localhost\r\n"
        "Content-Type: application/json\r\nTransfer-Encoding: chunked\r\n\r\n";
    const std::string chunk = std::string("10000\r\n").append(0x10000, ' ') + "\r\n";  // 64 KB
    SECTION("a little past: read to its end and answered") {
        RawConnection c(server.port());
        REQUIRE(c.send(head + chunk + chunk + "0\r\n\r\n"));
        c.closed_within(2s);
        CHECK_THAT(c.received(), Catch::StartsWith("HTTP/1.1 400") && Catch::Contains("too large"));
    }
    SECTION("far past: cut off after a megabyte, long before the 64 MB it would send") {
        // What the sockets' buffers take after the server closed (a few MB on loopback) still
        // counts as sent here.
        RawConnection c(server.port());
        REQUIRE(c.send(head));
        int sent = 0;
        while (sent < 1024 && c.send(chunk))
            ++sent;
        CHECK(sent < 256);
    }
}

TEST_CASE("a body that stops arriving is cut at the body deadline", "[api][limits]") {
    FakeBackend backend;
    api::ApiServer server(backend, "127.0.0.1", 0, small_limits());
    RawConnection c(server.port());
    REQUIRE(
        c.send("POST /api/session HTTP/1.1\r\nHost: localhost\r\n"
               "Content-Type: application/json\r\nContent-Length: 1000\r\n\r\n{\"user\""));
    const auto t0 = Clock::now();
    CHECK(c.closed_within(4s));
    CHECK(Clock::now() - t0 > 1500ms);  // 2 s body deadline, not the 1 s header one
}

TEST_CASE("a flood of sign-ins waits on its own lane: the status is answered meanwhile",
          "[api][limits]") {
    FakeBackend backend;
    // Slow hashes, as on a line: each sign-in takes a while.
    api::ApiServer server(backend, "127.0.0.1", 0, sign_in_flood(200000));
    Client operator_client(server.port());
    const auto h = operator_client.session("olga");
    std::vector<std::thread> flood;
    std::atomic<int> answered{0};
    for (int i = 0; i < 12; ++i)
        flood.emplace_back([&] {
            httplib::Client c("127.0.0.1", server.port());
            c.set_read_timeout(60, 0);
            const auto r =
                c.Post("/api/session", test::json{{"user", "olga"}, {"password", "wrong"}}.dump(),
                       "application/json");
            if (r) ++answered;
        });
    std::this_thread::sleep_for(100ms);
    CHECK(worst_status(operator_client, h, 10) < 500ms);
    for (auto& t : flood)
        t.join();
    CHECK(answered == 12);
}

TEST_CASE("one session cannot take every event stream", "[api][limits][events]") {
    FakeBackend backend;
    api::ApiServer server(backend, "127.0.0.1", 0, small_limits());
    Client c(server.port());
    const auto viewer = c.session("vera");
    std::vector<std::unique_ptr<RawConnection>> streams;
    std::string cookie = viewer.find("Cookie")->second;
    int refused = 0;
    for (int i = 0; i < 4; ++i) {
        streams.push_back(std::make_unique<RawConnection>(server.port()));
        streams.back()->send("GET /api/events HTTP/1.1\r\nHost: localhost\r\nCookie: " + cookie +
                             "\r\n\r\n");
        streams.back()->closed_within(300ms);
        refused += streams.back()->received().starts_with("HTTP/1.1 503");
    }
    CHECK(refused == 2);  // 2 per session
    // Another session still gets one.
    const auto op = c.session("olga");
    RawConnection other(server.port());
    other.send("GET /api/events HTTP/1.1\r\nHost: localhost\r\nCookie: " +
               op.find("Cookie")->second + "\r\n\r\n");
    other.closed_within(300ms);
    CHECK_THAT(other.received(), Catch::StartsWith("HTTP/1.1 200"));
}

TEST_CASE(
    "one client's requests queued past a quarter of the address's slots make room for "
    "a new client from that address",
    "[api][limits]") {
    FakeBackend backend;
    // Slow hashes (about 0.3 s) on the sign-in lane's one thread: the flood's requests wait
    // there, none idle, none answered before the operator comes.
    api::AccessSettings a = sign_in_flood(1500000);
    a.limits.connections_per_address = 8;
    api::ApiServer server(backend, "127.0.0.1", 0, a);
    Client operator_client(server.port());
    const auto h = operator_client.session("olga");
    const std::string body = R"({"user":"olga","password":"wrong"})";
    std::vector<std::unique_ptr<RawConnection>> flood;
    for (int i = 0; i < 8; ++i) {  // the per-address cap
        flood.push_back(std::make_unique<RawConnection>(server.port()));
        REQUIRE(flood.back()->send(
            "POST /api/session HTTP/1.1\r\nHost: localhost\r\nContent-Type: application/json\r\n"
            "Content-Length: " +
            std::to_string(body.size()) + "\r\n\r\n" + body));
    }
    std::this_thread::sleep_for(200ms);
    // The operator, from the same address on a new connection, is answered at once: without
    // room made it was refused at accept until the flood's hashes were done.
    RawConnection panel(server.port());
    REQUIRE(panel.send("GET /api/status HTTP/1.1\r\nHost: localhost\r\nCookie: " +
                       h.find("Cookie")->second + "\r\nConnection: close\r\n\r\n"));
    CHECK(panel.closed_within(500ms));
    CHECK_THAT(panel.received(), Catch::StartsWith("HTTP/1.1 200"));
    // Room was made from the flood's requests, cut without being run: closed with no answer.
    int cut = 0;
    for (auto& c : flood)
        cut += c->closed_within(20ms) && c->received().empty();
    CHECK(cut >= 1);
    CHECK(cut <= 6);
}
