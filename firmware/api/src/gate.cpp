#include "gate.hpp"

#include <openssl/crypto.h>

#include <algorithm>
#include <cctype>
#include <regex>

#include "routes.hpp"
#include "tilejet/api/job_request.hpp"
#include "tilejet/api/password.hpp"

namespace tilejet::api {

namespace {

struct Permission {
    const char* method;
    std::regex path;
    Role role;
};

// Everything under /api/ needs a session; what is not listed here needs the engineer role if
// it changes state and any role if it only reads, so a new route is closed until listed.
const std::vector<Permission>& permissions() {
    static const std::vector<Permission> table{
        {"POST", std::regex("/api/jobs"), Role::operator_},
        {"POST", std::regex("/api/line/[a-z]+"), Role::operator_},
        {"DELETE", std::regex("/api/session"), Role::viewer},
        {"PUT", std::regex("/api/designs/[^/]+"), Role::engineer},
        {"PUT", std::regex("/api/profiles/[^/]+"), Role::engineer},
        {"POST", std::regex("/api/config/reload"), Role::engineer},
    };
    return table;
}

bool changes_state(const std::string& method) {
    return method != "GET" && method != "HEAD" && method != "OPTIONS";
}

Role required_role(const HttpRequest& req) {
    for (const Permission& p : permissions())
        if (req.method == p.method && std::regex_match(req.path, p.path)) return p.role;
    return changes_state(req.method) ? Role::engineer : Role::viewer;
}

std::optional<std::string> cookie(const HttpRequest& req, std::string_view name) {
    const std::string header = req.get_header_value("Cookie");
    size_t pos = 0;
    while (pos < header.size()) {
        size_t end = header.find(';', pos);
        if (end == std::string::npos) end = header.size();
        std::string_view item(header.data() + pos, end - pos);
        while (!item.empty() && item.front() == ' ')
            item.remove_prefix(1);
        if (item.size() > name.size() && item.starts_with(name) && item[name.size()] == '=')
            return std::string(item.substr(name.size() + 1));
        pos = end + 1;
    }
    return std::nullopt;
}

}  // namespace

std::optional<std::string> session_cookie(const HttpRequest& req) {
    return cookie(req, kSessionCookie);
}

namespace {

bool same_token(const std::string& a, const std::string& b) {
    return a.size() == b.size() && CRYPTO_memcmp(a.data(), b.data(), a.size()) == 0;
}

std::string text_field(const nlohmann::json& j, const char* field, size_t max) {
    if (!j.contains(field)) throw ApiError(400, field, std::string(field) + ": missing (required)");
    if (!j[field].is_string())
        throw ApiError(400, field, std::string(field) + ": expected a string");
    std::string s = j[field].get<std::string>();
    if (s.empty() || s.size() > max)
        throw ApiError(400, field,
                       std::string(field) + ": must be 1.." + std::to_string(max) + " characters");
    return s;
}

}  // namespace

namespace {

std::string lower(std::string s) {
    for (char& c : s)
        c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

// "name:port", "[v6]:port" or "name" -> "name" / "[v6]".
std::string host_part(const std::string& authority) {
    if (authority.starts_with('[')) {
        const size_t end = authority.find(']');
        return end == std::string::npos ? authority : authority.substr(0, end + 1);
    }
    return authority.substr(0, authority.find(':'));
}

}  // namespace

std::optional<std::string> Gate::foreign_host(const HttpRequest& req) const {
    const auto known = [&](const std::string& name) {
        return std::find(host_names_.begin(), host_names_.end(), lower(name)) != host_names_.end();
    };
    const std::string host = req.get_header_value("Host");
    if (!known(host_part(host)))
        return "Host '" + host + "' is not one of this controller's names ([api] host_names)";
    if (req.has_header("Origin")) {
        const std::string origin = req.get_header_value("Origin");
        const size_t scheme = origin.find("://");
        if (scheme == std::string::npos || !known(host_part(origin.substr(scheme + 3))))
            return "Origin '" + origin +
                   "' is not one of this controller's names ([api] host_names)";
    }
    return std::nullopt;
}

Gate::Gate(const AccessSettings& settings)
    : settings_(settings.sessions), sessions_(settings.sessions), limiter_(settings.sign_in) {
    for (const std::string& name : settings.host_names)
        host_names_.push_back(lower(name));
    int iterations = 1;
    for (const User& u : settings.users) {
        try {
            check_password_hash(u.password_hash);
        } catch (const std::exception& e) {
            throw std::invalid_argument("user '" + u.name + "': " + e.what());
        }
        if (!users_.emplace(u.name, u).second)
            throw std::invalid_argument("user '" + u.name + "' appears twice");
        const auto first = u.password_hash.find('$') + 1;
        iterations = std::max(iterations, std::stoi(u.password_hash.substr(first)));
    }
    dummy_hash_ = hash_password(random_token(), iterations);
}

bool Gate::check(const HttpRequest& req, HttpResponse& res) {
    if (!req.path.starts_with("/api/")) return false;
    if (const auto why = foreign_host(req)) {
        reply_error(res, 403, "host", *why);
        return true;
    }
    if (req.path == "/api/session" && req.method == "POST") return false;
    // The event stream is no activity of the user's: an open panel alone must not keep a
    // session from going idle.
    const auto s = session(req, req.path != "/api/events");
    if (!s) {
        reply_error(res, 401, "session", "sign in first");
        return true;
    }
    if (changes_state(req.method) && !same_token(req.get_header_value(kCsrfHeader), s->csrf)) {
        reply_error(res, 403, "csrf",
                    std::string("missing or wrong ") + kCsrfHeader + " header (sign in again)");
        return true;
    }
    const Role needed = required_role(req);
    if (s->role < needed) {
        reply_error(res, 403, "role",
                    "a " + std::string(to_string(s->role)) + " may not do this; it needs a" +
                        (needed == Role::engineer ? "n " : " ") + std::string(to_string(needed)));
        return true;
    }
    return false;
}

Session Gate::sign_in(const HttpRequest& req) {
    // A form from another site cannot send application/json without asking first (CORS), so
    // nobody can sign a browser in under an account of theirs from their page.
    if (req.get_header_value("Content-Type").find("application/json") != 0)
        throw ApiError(400, "body", "body: expected Content-Type application/json");
    nlohmann::json j = nlohmann::json::parse(req.body, nullptr, false);
    if (j.is_discarded()) throw ApiError(400, "body", "body: malformed JSON");
    if (!j.is_object()) throw ApiError(400, "body", "body: expected a JSON object");
    for (const auto& [key, value] : j.items())
        if (key != "user" && key != "password") throw ApiError(400, key, key + ": unknown field");
    const std::string user = text_field(j, "user", 64);
    const std::string password = text_field(j, "password", 1024);

    if (const auto wait = limiter_.begin(req.remote_addr, user); wait.count() > 0)
        throw ApiError(
            429, "user",
            "too many failed sign-ins; try again in " + std::to_string(wait.count()) + " s");
    const auto it = users_.find(user);
    const bool ok =
        verify_password(password, it == users_.end() ? dummy_hash_ : it->second.password_hash) &&
        it != users_.end();
    if (!ok) throw ApiError(401, "password", "unknown user or wrong password");
    limiter_.succeeded(req.remote_addr, user);
    return sessions_.open(it->second);
}

std::optional<Session> Gate::session(const HttpRequest& req, bool touch) {
    const auto id = session_cookie(req);
    if (!id) return std::nullopt;
    return sessions_.find(*id, touch);
}

void Gate::sign_out(const HttpRequest& req) {
    if (const auto id = session_cookie(req)) sessions_.close(*id);
}

}  // namespace tilejet::api
