#pragma once

// The gate every request passes before its route: sessions, CSRF tokens and roles, decided in
// one place (kPermissions in gate.cpp) so that no route can forget them.
#include <map>
#include <optional>

#include "http_message.hpp"
#include "sessions.hpp"
#include "sign_in_limiter.hpp"
#include "tilejet/api/api_server.hpp"

namespace tilejet::api {

inline constexpr const char* kSessionCookie = "tilejet_session";
inline constexpr const char* kCsrfHeader = "X-CSRF-Token";

// The session id the request's cookie carries.
std::optional<std::string> session_cookie(const HttpRequest& req);

class Gate {
  public:
    // Throws std::invalid_argument on a duplicate user name or a malformed password hash.
    explicit Gate(const AccessSettings& settings);

    // Before routing, with the headers only: answers 403 (a Host or Origin not of this
    // controller), 401 (no session), 403 (CSRF token or role) itself and returns true; false
    // lets the request reach its route.
    bool check(const HttpRequest& req, HttpResponse& res);

    // POST /api/session: throws ApiError 400 (body), 401 (user or password), 429 (too many).
    Session sign_in(const HttpRequest& req);
    std::optional<Session> session(const HttpRequest& req, bool touch = true);
    void sign_out(const HttpRequest& req);
    // Whether the session with this id is still signed in (event streams ask as they go on).
    bool alive(const std::string& id) { return sessions_.find(id, false).has_value(); }
    std::chrono::seconds session_lifetime() const { return settings_.lifetime; }

  private:
    // Why the request's Host or Origin is not one of host_names_, or nothing.
    std::optional<std::string> foreign_host(const HttpRequest& req) const;

    std::vector<std::string> host_names_;  // lower case
    std::map<std::string, User> users_;
    std::string dummy_hash_;  // verified against for unknown users: same time as a known one
    SessionSettings settings_;
    SessionStore sessions_;
    SignInLimiter limiter_;
};

}  // namespace tilejet::api
