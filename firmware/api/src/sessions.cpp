#include "sessions.hpp"

#include <openssl/rand.h>

#include <algorithm>
#include <stdexcept>

namespace tilejet::api {

std::string random_token() {
    unsigned char bytes[32];
    if (RAND_bytes(bytes, sizeof bytes) != 1) throw std::runtime_error("no random bytes");
    static const char* hex = "0123456789abcdef";
    std::string out;
    for (unsigned char b : bytes) {
        out += hex[b >> 4];
        out += hex[b & 15];
    }
    return out;
}

bool SessionStore::expired(const Session& s, std::chrono::steady_clock::time_point now) const {
    return now - s.last_seen > settings_.idle || now - s.created > settings_.lifetime;
}

Session SessionStore::open(const User& user) {
    const auto now = std::chrono::steady_clock::now();
    Session s{random_token(), random_token(), user.name, user.role, now, now};
    std::lock_guard lock(mutex_);
    std::erase_if(sessions_, [&](const auto& entry) { return expired(entry.second, now); });
    // Capped per user, the user's own oldest signed out first: a viewer signing in again and
    // again must not sign the operator out. Users are the config's few, so this bounds all.
    const auto mine = [&](const auto& entry) { return entry.second.user == user.name; };
    while (std::count_if(sessions_.begin(), sessions_.end(), mine) >=
           std::max(1, settings_.max_sessions)) {
        auto oldest = sessions_.end();
        for (auto it = sessions_.begin(); it != sessions_.end(); ++it)
            if (mine(*it) &&
                (oldest == sessions_.end() || it->second.last_seen < oldest->second.last_seen))
                oldest = it;
        sessions_.erase(oldest);
    }
    sessions_.emplace(s.id, s);
    return s;
}

std::optional<Session> SessionStore::find(std::string_view id, bool touch) {
    const auto now = std::chrono::steady_clock::now();
    std::lock_guard lock(mutex_);
    const auto it = sessions_.find(id);
    if (it == sessions_.end()) return std::nullopt;
    if (expired(it->second, now)) {
        sessions_.erase(it);
        return std::nullopt;
    }
    if (touch) it->second.last_seen = now;
    return it->second;
}

void SessionStore::close(std::string_view id) {
    std::lock_guard lock(mutex_);
    const auto it = sessions_.find(id);
    if (it != sessions_.end()) sessions_.erase(it);
}

}  // namespace tilejet::api
