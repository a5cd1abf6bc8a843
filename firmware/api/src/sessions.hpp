#pragma once

// Signed-in sessions, in memory: a restart signs everybody out, which is what a restarted
// print controller should do anyway.
#include <chrono>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

#include "tilejet/api/access.hpp"

namespace tilejet::api {

struct Session {
    std::string id;    // the cookie's value
    std::string csrf;  // what state-changing requests must carry in X-CSRF-Token
    std::string user;
    Role role = Role::viewer;
    std::chrono::steady_clock::time_point created, last_seen;
};

// 32 random bytes as hex: for session ids and CSRF tokens.
std::string random_token();

class SessionStore {
  public:
    explicit SessionStore(const SessionSettings& settings) : settings_(settings) {}
    Session open(const User& user);
    // The live session with this id; `touch` counts the request as activity (idle timeout).
    std::optional<Session> find(std::string_view id, bool touch = true);
    void close(std::string_view id);

  private:
    bool expired(const Session& s, std::chrono::steady_clock::time_point now) const;
    SessionSettings settings_;
    std::mutex mutex_;
    std::map<std::string, Session, std::less<>> sessions_;
};

}  // namespace tilejet::api
