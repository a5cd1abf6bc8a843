#pragma once

// Who may do what: users and roles from the config, and the session and sign-in limits.
//   viewer    sees the panel (an office screen, a supervisor)
//   operator  runs the line: submits jobs of existing designs, pause, resume, stop, acknowledge
//   engineer  also sets up the line: uploads designs and profiles, reloads the config
#include <chrono>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tilejet::api {

enum class Role { viewer, operator_, engineer };  // ordered: each may do what those before may
std::optional<Role> parse_role(std::string_view text);
std::string_view to_string(Role role);
std::vector<std::string> role_names();  // every role, for config choices and messages

struct User {
    std::string name;
    Role role = Role::viewer;
    std::string password_hash;  // see password.hpp
};

struct SessionSettings {
    // A panel left signed in on the line is somebody else's hands on it after a shift change.
    std::chrono::seconds idle{std::chrono::hours(2)};
    std::chrono::seconds lifetime{std::chrono::hours(12)};
    int max_sessions = 16;  // per user; the user's oldest signed out first when full
};

struct SignInLimits {
    int failures_per_user = 5;      // failed sign-ins per user per window, then 429
    int failures_per_address = 20;  // per client address: guessing across many user names
    std::chrono::seconds window{60};
};

// What any one client may make the HTTP server spend ([api] in the config; http_server.hpp).
struct ServerLimits {
    int connections = 512;              // open at once, all clients
    int connections_per_address = 128;  // from one client address
    // A request's line and headers must have arrived this long after the connection opened
    // (or its previous answer went out), and its body this long after its headers.
    std::chrono::seconds header_timeout{10};
    std::chrono::seconds body_timeout{60};
    // Event streams (/api/events) open at once, in all and per session.
    int event_streams = 32;
    int event_streams_per_session = 4;
};

// Everything about who gets in and what each may take, for ApiServer.
struct AccessSettings {
    std::vector<User> users;
    SessionSettings sessions;
    SignInLimits sign_in;
    // The names a request's Host header (and its Origin, when a browser sends one) may give,
    // without port: anything else is refused, so that a page of another site whose name was
    // rebound to this address (DNS rebinding) cannot use the API. [api] host and host_names.
    std::vector<std::string> host_names{"localhost", "127.0.0.1", "[::1]"};
    ServerLimits limits;
};

}  // namespace tilejet::api
