// The API server in this process over a backend the test controls: sign-in, sessions, CSRF
// tokens, roles, request validation and the event stream.
#include <httplib.h>

#include <algorithm>
#include <atomic>
#include <catch2/catch.hpp>
#include <thread>

#include "api_fixtures.hpp"
#include "tilejet/api/api_server.hpp"
#include "tilejet/api/job_request.hpp"
#include "tilejet/api/password.hpp"

using namespace tilejet;
using namespace std::chrono_literals;
using nlohmann::json;

using test::access;
using test::Answer;
using test::Client;
using test::FakeBackend;

namespace {

const std::string kJob = R"({"map":"a.tjmap","seed":1,"tiles":2,"tile_mm":"100x100"})";

struct Endpoint {
    const char* method;
    const char* path;
    std::string body;
    api::Role role;
};

// Every route that changes something, with the least role that may call it.
const std::vector<Endpoint>& state_changing() {
    static const std::vector<Endpoint> list{
        {"POST", "/api/jobs", kJob, api::Role::operator_},
        {"POST", "/api/line/pause", "", api::Role::operator_},
        {"POST", "/api/line/resume", "", api::Role::operator_},
        {"POST", "/api/line/stop", "", api::Role::operator_},
        {"POST", "/api/line/acknowledge", "", api::Role::operator_},
        {"PUT", "/api/designs/new.tjmap", "not a map", api::Role::engineer},
        {"PUT", "/api/profiles/new.icc", "not a profile", api::Role::engineer},
        {"POST", "/api/config/reload", "", api::Role::engineer},
        {"DELETE", "/api/session", "", api::Role::viewer},
    };
    return list;
}

const char* user_of(api::Role role) {
    return role == api::Role::engineer ? "erik" : role == api::Role::operator_ ? "olga" : "vera";
}

}  // namespace

TEST_CASE("every state-changing endpoint wants a session, its CSRF token and the right role",
          "[api][auth]") {
    FakeBackend backend;
    api::ApiServer server(backend, "127.0.0.1", 0, access());
    Client c(server.port());
    for (const Endpoint& e : state_changing()) {
        INFO(e.method << " " << e.path);
        // No session at all.
        Answer a = c.send(e.method, e.path, e.body);
        CHECK(a.status == 401);
        CHECK(a.body["field"] == "session");
        // A session cookie that was never issued.
        a = c.send(e.method, e.path, e.body,
                   {{"Cookie", "tilejet_session=00112233"}, {"X-CSRF-Token", "00112233"}});
        CHECK(a.status == 401);
        // The right role, but no CSRF token, or another session's.
        const char* user = user_of(e.role);
        a = c.send(e.method, e.path, e.body, c.session(user, false));
        CHECK(a.status == 403);
        CHECK(a.body["field"] == "csrf");
        auto mixed = c.session(user, false);
        mixed.emplace("X-CSRF-Token", c.session(user).find("X-CSRF-Token")->second);
        CHECK(c.send(e.method, e.path, e.body, mixed).status == 403);
        // A role below the one needed.
        if (e.role != api::Role::viewer) {
            const auto lower = api::Role(int(e.role) - 1);
            a = c.send(e.method, e.path, e.body, c.session(user_of(lower)));
            CHECK(a.status == 403);
            CHECK(a.body["field"] == "role");
        }
        // The right role with its token gets past the gate to the handler.
        a = c.send(e.method, e.path, e.body, c.session(user));
        CHECK(a.status != 401);
        CHECK(a.status != 403);
    }
    // Nothing reached the backend's job queue or line but the allowed calls.
    CHECK(backend.submitted == 1);
    CHECK(backend.last_command == "acknowledge");
}

TEST_CASE("reading needs a session of any role", "[api][auth]") {
    FakeBackend backend;
    api::ApiServer server(backend, "127.0.0.1", 0, access());
    Client c(server.port());
    for (const char* path : {"/api/status", "/api/jobs", "/api/designs", "/api/events"}) {
        INFO(path);
        CHECK(c.send("GET", path).status == 401);
    }
    CHECK(c.send("GET", "/api/status", "", c.session("vera")).body["state"] == "idle");
}

TEST_CASE("sign-in: cookie flags, wrong passwords, malformed bodies, sign-out", "[api][auth]") {
    FakeBackend backend;
    api::ApiServer server(backend, "127.0.0.1", 0, access());
    Client c(server.port());

    const Answer ok = c.sign_in("olga", "olga-pw-123");
    REQUIRE(ok.status == 200);
    CHECK(ok.body["role"] == "operator");
    const std::string cookie = ok.headers.find("Set-Cookie")->second;
    CHECK_THAT(cookie, Catch::Contains("HttpOnly"));
    CHECK_THAT(cookie, Catch::Contains("SameSite=Strict"));
    CHECK_THAT(cookie, Catch::StartsWith("tilejet_session="));
    // The token is not the session id: a page that leaks one does not leak the other.
    CHECK(cookie.find(ok.body["csrf"].get<std::string>()) == std::string::npos);

    CHECK(c.sign_in("olga", "olga-pw-124").status == 401);
    CHECK(c.sign_in("nobody", "olga-pw-123").status == 401);
    Answer a = c.send("POST", "/api/session", R"({"user":"olga","password":"x","remember":1})");
    CHECK(a.status == 400);
    CHECK(a.body["field"] == "remember");
    a = c.send("POST", "/api/session", R"({"user":"olga",)");
    CHECK(a.status == 400);
    CHECK(a.body["field"] == "body");
    a = c.send("POST", "/api/session", R"({"user":"olga"})");
    CHECK(a.status == 400);
    CHECK(a.body["field"] == "password");
    a = c.send("POST", "/api/session", R"({"user":7,"password":"x"})");
    CHECK(a.status == 400);
    CHECK(a.body["field"] == "user");
    // What a cross-site form could send is refused before any password is looked at.
    a = c.send("POST", "/api/session", "user=olga&password=olga-pw-123", {},
               "application/x-www-form-urlencoded");
    CHECK(a.status == 400);

    const auto h = c.session("olga");
    CHECK(c.send("GET", "/api/session", "", h).body["user"] == "olga");
    CHECK(c.send("DELETE", "/api/session", "", h).status == 200);
    CHECK(c.send("GET", "/api/status", "", h).status == 401);
    CHECK(c.send("POST", "/api/line/pause", "", h).status == 401);
}

TEST_CASE("sign-in attempts are limited per user, the right password included", "[api][auth]") {
    FakeBackend backend;
    api::ApiServer server(backend, "127.0.0.1", 0, access());
    Client c(server.port());
    for (int i = 0; i < 3; ++i)
        CHECK(c.sign_in("olga", "guess-" + std::to_string(i)).status == 401);
    const Answer blocked = c.sign_in("olga", "olga-pw-123");
    CHECK(blocked.status == 429);
    CHECK_THAT(blocked.body["error"].get<std::string>(), Catch::Contains("try again"));
    // Another user from the same address is not locked out by olga's failures.
    CHECK(c.sign_in("erik", "erik-pw-123").status == 200);
}

TEST_CASE("sign-in attempts are limited per client address across user names", "[api][auth]") {
    FakeBackend backend;
    auto a = access();
    a.sign_in.failures_per_address = 4;
    api::ApiServer server(backend, "127.0.0.1", 0, a);
    Client c(server.port());
    for (int i = 0; i < 4; ++i)
        CHECK(c.sign_in("user" + std::to_string(i), "guess").status == 401);
    CHECK(c.sign_in("erik", "erik-pw-123").status == 429);
}

TEST_CASE("malformed JSON, unknown fields, bad values and oversize bodies name the field",
          "[api][validation]") {
    FakeBackend backend;
    api::ApiServer server(backend, "127.0.0.1", 0, access());
    Client c(server.port());
    const auto h = c.session("olga");
    struct Case {
        std::string body;
        int status;
        const char* field;
    };
    const std::vector<Case> cases{
        {R"({"map":"a.tjmap","seed":1,)", 400, "body"},
        {R"([1,2])", 400, "body"},
        {R"({"map":"a.tjmap","seed":1,"tiles":2,"tile_mm":"100x100","colour":"red"})", 400,
         "colour"},
        {R"({"map":"a.tjmap","seed":1,"tiles":0,"tile_mm":"100x100"})", 400, "tiles"},
        {R"({"map":"/maps/a.tjmap","seed":1,"tiles":2,"tile_mm":"100x100"})", 400, "map"},
        {R"({"map":"../a.tjmap","seed":1,"tiles":2,"tile_mm":"100x100"})", 400, "map"},
        {R"({"map":"/dev/zero","seed":1,"tiles":2,"tile_mm":"100x100"})", 400, "map"},
        {R"({"map":"a.tjmap","seed":1,"tiles":2,"tile_mm":"100by100"})", 400, "tile_mm"},
        {R"({"map":"a.tjmap","seed":1,"tiles":2,"tile_mm":"100x100","layout":"grid"})", 400,
         "layout"},
        {std::string("{\"map\":\"/").append(70 * 1024, 'a') + "\"}", 400, "body"},
    };
    for (const Case& k : cases) {
        INFO(k.body.substr(0, 120));
        const Answer a = c.send("POST", "/api/jobs", k.body, h);
        CHECK(a.status == k.status);
        CHECK(a.body["field"] == k.field);
    }
    Answer a = c.send("POST", "/api/line/pause", R"({"now":true})", h);
    CHECK(a.status == 400);
    CHECK(a.body["field"] == "body");
    a = c.send("GET", "/api/wall.png?tiles=1000", "", h);
    CHECK(a.status == 400);
    CHECK(a.body["field"] == "tiles");
    CHECK(backend.submitted == 0);
}

TEST_CASE("errors quoting bytes that are not UTF-8 are answered, not the end of the server",
          "[api][validation]") {
    // Found by fuzz_api_request: these messages quote what the client sent, and turning them
    // into JSON threw from the exception handler, which ended the process.
    FakeBackend backend;
    api::ApiServer server(backend, "127.0.0.1", 0, access());
    Client c(server.port());
    const auto h = c.session("olga");
    // The JSON parser's message quotes the ill-formed key ("last read: ...").
    Answer a = c.send("POST", "/api/jobs",
                      "{\"map\":\"/maps/a.tjmap\",\"seed\":7,\"tiles\":50,\"tile_mm\":\"300x300\","
                      "\"dp\xe9\":100}",
                      h);
    CHECK(a.status == 400);
    CHECK(a.body["field"] == "body");
    // A viewer's reads quote the path and the query.
    a = c.send("GET", "/api/jobs/%E9", "", c.session("vera"));
    CHECK(a.status == 400);
    CHECK(a.body["field"] == "id");
    CHECK_THAT(a.body["error"].get<std::string>(), Catch::Contains("\xef\xbf\xbd"));  // U+FFFD
    a = c.send("GET", "/api/wall.png?tiles=%E9", "", h);
    CHECK(a.status == 400);
    CHECK(a.body["field"] == "tiles");
    CHECK(c.send("GET", "/api/status", "", h).status == 200);
    CHECK(backend.submitted == 0);
}

namespace {

// An /api/events reader on its own thread, collecting what arrives.
class EventReader {
  public:
    EventReader(int port, httplib::Headers headers) : client_("127.0.0.1", port) {
        client_.set_read_timeout(30, 0);
        thread_ = std::thread([this, headers] {
            auto r = client_.Get(
                "/api/events", headers,
                [this](const httplib::Response& res) {
                    status_ = res.status;
                    return res.status == 200;
                },
                [this](const char* data, size_t n) {
                    std::lock_guard lock(mutex_);
                    text_.append(data, n);
                    return !stop_;
                });
            ended_ = true;
        });
    }
    ~EventReader() {
        stop_ = true;
        client_.stop();
        thread_.join();
    }
    std::string text() {
        std::lock_guard lock(mutex_);
        return text_;
    }
    int status() const { return status_; }
    bool ended() const { return ended_; }

  private:
    httplib::Client client_;
    std::mutex mutex_;
    std::string text_;
    std::atomic<int> status_{0};
    std::atomic<bool> stop_{false}, ended_{false};
    std::thread thread_;
};

bool eventually(const std::function<bool()>& condition, std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
        if (condition()) return true;
        std::this_thread::sleep_for(20ms);
    }
    return condition();
}

}  // namespace

TEST_CASE("the event stream delivers state changes as they happen", "[api][events]") {
    FakeBackend backend;
    api::ApiServer server(backend, "127.0.0.1", 0, access());
    Client c(server.port());
    EventReader events(server.port(), c.session("vera"));
    REQUIRE(
        eventually([&] { return events.text().find("\"counter\":0") != std::string::npos; }, 5s));
    CHECK(events.status() == 200);
    CHECK_THAT(events.text(), Catch::Contains("event: status\ndata: {"));
    CHECK_THAT(events.text(), Catch::Contains("event: jobs\ndata: []"));
    backend.counter = 41;
    CHECK(
        eventually([&] { return events.text().find("\"counter\":41") != std::string::npos; }, 5s));
    // Nothing changes, nothing is sent again.
    std::this_thread::sleep_for(600ms);
    const std::string text = events.text();
    size_t count = 0;
    for (size_t at = text.find("event: status"); at != std::string::npos;
         at = text.find("event: status", at + 1))
        ++count;
    CHECK(count == 2);
}

TEST_CASE("open event streams neither starve the API nor hold up a shutdown", "[api][events]") {
    FakeBackend backend;
    auto server = std::make_unique<api::ApiServer>(backend, "127.0.0.1", 0, access(2));
    Client c(server->port());
    const auto h = c.session("vera");
    EventReader a(server->port(), h), b(server->port(), h);
    REQUIRE(eventually([&] { return !a.text().empty() && !b.text().empty(); }, 5s));
    // Past the limit a new stream is told to come back later...
    Answer third = c.send("GET", "/api/events", "", h);
    CHECK(third.status == 503);
    // ...and plain requests are still answered at once.
    for (int i = 0; i < 20; ++i)
        REQUIRE(c.send("GET", "/api/status", "", h).status == 200);
    const auto start = std::chrono::steady_clock::now();
    server.reset();
    CHECK(std::chrono::steady_clock::now() - start < 4s);
    CHECK(eventually([&] { return a.ended() && b.ended(); }, 2s));
}

TEST_CASE("signing out ends that session's event stream", "[api][events]") {
    FakeBackend backend;
    api::ApiServer server(backend, "127.0.0.1", 0, access());
    Client c(server.port());
    const auto h = c.session("olga");
    EventReader events(server.port(), h);
    REQUIRE(eventually([&] { return !events.text().empty(); }, 5s));
    CHECK(c.send("DELETE", "/api/session", "", h).status == 200);
    backend.counter = 7;  // the stream wakes, finds the session gone and ends
    CHECK(eventually([&] { return events.ended(); }, 5s));
}

TEST_CASE("the panel's page is served with a policy that keeps it from being framed",
          "[api][panel]") {
    FakeBackend backend;
    api::ApiServer server(backend, "127.0.0.1", 0, access());
    httplib::Client c("127.0.0.1", server.port());
    for (const char* path : {"/", "/panel.js", "/panel.css"}) {
        INFO(path);
        const auto r = c.Get(path);
        REQUIRE(r);
        CHECK(r->status == 200);
        CHECK_FALSE(r->body.empty());
        CHECK_THAT(r->get_header_value("Content-Security-Policy"),
                   Catch::Contains("frame-ancestors 'none'"));
    }
    const auto page = c.Get("/");
    CHECK_THAT(page->get_header_value("Content-Type"), Catch::StartsWith("text/html"));
    CHECK_THAT(page->body, Catch::Contains("panel.js"));
}

TEST_CASE("parallel wrong passwords for one user: the limit is checked and counted at once",
          "[api][auth]") {
    // The limit used to be checked before the slow password check and counted after it: 40
    // parallel guesses got 20 tries instead of the limit's 5.
    FakeBackend backend;
    api::ApiServer server(backend, "127.0.0.1", 0, access());  // 3 failures per user
    std::vector<int> statuses(12);  // fewer than the server's threads: all run at once
    std::vector<std::thread> guessers;
    for (size_t i = 0; i < statuses.size(); ++i)
        guessers.emplace_back([&, i] {
            httplib::Client c("127.0.0.1", server.port());
            c.set_read_timeout(20, 0);
            const auto r =
                c.Post("/api/session", json{{"user", "olga"}, {"password", "guess"}}.dump(),
                       "application/json");
            statuses[i] = r ? r->status : -1;
        });
    for (std::thread& t : guessers)
        t.join();
    INFO(json(statuses).dump());
    CHECK(std::count(statuses.begin(), statuses.end(), 401) == 3);
    CHECK(std::count(statuses.begin(), statuses.end(), 429) == 9);
}

TEST_CASE(
    "sessions are capped per user: a viewer signing in again and again signs nobody else "
    "out",
    "[api][auth]") {
    FakeBackend backend;
    api::ApiServer server(backend, "127.0.0.1", 0, access());
    Client c(server.port());
    const auto operator_session = c.session("olga");
    const auto first_viewer_session = c.session("vera");
    for (int i = 0; i < 80; ++i)
        c.session("vera");
    CHECK(c.send("GET", "/api/status", "", operator_session).status == 200);
    // The viewer's own oldest went to make room for the newer ones.
    CHECK(c.send("GET", "/api/status", "", first_viewer_session).status == 401);
}

TEST_CASE("a request whose Host or Origin is not the controller's is refused, sign-in included",
          "[api][auth]") {
    // A page of evil.example whose name was rebound to 127.0.0.1 sends its own name as Host and
    // Origin: with the demo accounts it could otherwise sign in and drive the line.
    FakeBackend backend;
    api::ApiServer server(backend, "127.0.0.1", 0, access());
    Client c(server.port());
    const std::string port = std::to_string(server.port());
    const std::string body = json{{"user", "olga"}, {"password", "olga-pw-123"}}.dump();
    Answer a =
        c.send("POST", "/api/session", body,
               {{"Host", "evil.example:" + port}, {"Origin", "http://evil.example:" + port}});
    CHECK(a.status == 403);
    CHECK(a.body["field"] == "host");
    CHECK_THAT(a.body["error"].get<std::string>(), Catch::Contains("evil.example"));
    a = c.send("POST", "/api/session", body, {{"Origin", "http://evil.example:" + port}});
    CHECK(a.status == 403);
    const auto h = c.session("olga");
    auto with = [&](httplib::Headers extra) {
        extra.insert(h.begin(), h.end());
        return extra;
    };
    CHECK(c.send("GET", "/api/status", "", with({{"Host", "evil.example"}})).status == 403);
    CHECK(c.send("POST", "/api/line/pause", "", with({{"Origin", "null"}})).status == 403);
    // The controller's own names pass, with or without port, in any case.
    CHECK(c.send("GET", "/api/status", "", with({{"Host", "LOCALHOST:" + port}})).status == 200);
    CHECK(c.send("POST", "/api/line/pause", "", with({{"Origin", "http://127.0.0.1:" + port}}))
              .status == 200);
}
