#pragma once

// The API server's tests' fixtures: a backend the test controls, users of each role, and a
// client that signs in.
#include <httplib.h>

#include <atomic>
#include <catch2/catch.hpp>
#include <string>

#include "tilejet/api/api_server.hpp"
#include "tilejet/api/password.hpp"

namespace tilejet::test {

using nlohmann::json;

class FakeBackend : public api::ApiBackend {
  public:
    json status() override { return {{"state", "idle"}, {"counter", counter.load()}}; }
    json submit(const jobs::JobSpec& spec) override {
        ++submitted;
        return {{"id", 1}, {"tiles", spec.tiles}};
    }
    json jobs() override { return json::array(); }
    std::optional<json> job(std::int64_t) override { return std::nullopt; }
    json command(std::string_view name) override {
        last_command = std::string(name);
        return {{"accepted", last_command}};
    }
    int default_dpi() const override { return 100; }
    json reload_config() override { return {{"reload", "requested"}}; }

    std::atomic<int> counter{0};
    std::atomic<int> submitted{0};
    std::string last_command;
};

inline api::AccessSettings access(int streams = 3) {
    api::AccessSettings a;
    a.users = {{"olga", api::Role::operator_, api::hash_password("olga-pw-123", 1000)},
               {"erik", api::Role::engineer, api::hash_password("erik-pw-123", 1000)},
               {"vera", api::Role::viewer, api::hash_password("vera-pw-123", 1000)}};
    a.sign_in.failures_per_user = 3;
    a.sign_in.failures_per_address = 100;
    a.limits.event_streams = streams;
    return a;
}

struct Answer {
    int status = 0;
    json body;
    httplib::Headers headers;
};

class Client {
  public:
    explicit Client(int port) : c_("127.0.0.1", port) {
        c_.set_connection_timeout(2, 0);
        c_.set_read_timeout(10, 0);
    }
    Answer send(const std::string& method, const std::string& path, const std::string& body = {},
                const httplib::Headers& headers = {}, const char* type = "application/json") {
        httplib::Result r = method == "GET"      ? c_.Get(path.c_str(), headers)
                            : method == "PUT"    ? c_.Put(path.c_str(), headers, body, type)
                            : method == "DELETE" ? c_.Delete(path.c_str(), headers)
                                                 : c_.Post(path.c_str(), headers, body, type);
        REQUIRE(r);
        return {r->status, json::parse(r->body, nullptr, false), r->headers};
    }
    Answer sign_in(const std::string& user, const std::string& password) {
        return send("POST", "/api/session", json{{"user", user}, {"password", password}}.dump());
    }
    // The headers of a signed-in client: cookie, and the CSRF token unless `csrf` is false.
    httplib::Headers session(const std::string& user, bool csrf = true) {
        const Answer a = sign_in(user, user + "-pw-123");
        REQUIRE(a.status == 200);
        const std::string cookie = a.headers.find("Set-Cookie")->second;
        httplib::Headers h{{"Cookie", cookie.substr(0, cookie.find(';'))}};
        if (csrf) h.emplace("X-CSRF-Token", a.body.at("csrf").get<std::string>());
        return h;
    }

  private:
    httplib::Client c_;
};

}  // namespace tilejet::test
