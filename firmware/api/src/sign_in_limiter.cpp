#include "sign_in_limiter.hpp"

#include <algorithm>

namespace tilejet::api {

namespace {

// Keys of both kinds share one map; the prefixes keep a user named like an address apart.
// (Appended rather than "literal" + string: GCC 12 warns falsely on that, bug 105329.)
std::string key(const char* kind, const std::string& name) {
    std::string k(kind);
    k += name;
    return k;
}
// A user's failures count per client address: a stranger guessing at the operator's name from
// elsewhere must not lock the operator out at the panel's own address.
std::string user_key(const std::string& address, const std::string& user) {
    std::string k = key("user:", address);
    k += '/';
    k += user;
    return k;
}
std::string address_key(const std::string& address) {
    return key("addr:", address);
}

// Bounds the memory a stream of made-up user names can take.
constexpr size_t kMaxKeys = 4096;

}  // namespace

std::chrono::seconds SignInLimiter::wait_for(const std::string& key, int limit,
                                             Clock::time_point now) {
    const auto it = failures_.find(key);
    if (it == failures_.end()) return std::chrono::seconds(0);
    auto& times = it->second;
    while (!times.empty() && now - times.front() >= limits_.window)
        times.pop_front();
    if (int(times.size()) < limit) return std::chrono::seconds(0);
    const auto free_at = times[times.size() - size_t(limit)] + limits_.window;
    return std::max(std::chrono::seconds(1),
                    std::chrono::ceil<std::chrono::seconds>(free_at - now));
}

std::chrono::seconds SignInLimiter::begin(const std::string& address, const std::string& user) {
    const auto now = Clock::now();
    std::lock_guard lock(mutex_);
    const auto wait = std::max(wait_for(user_key(address, user), limits_.failures_per_user, now),
                               wait_for(address_key(address), limits_.failures_per_address, now));
    if (wait.count() > 0) return wait;
    if (failures_.size() >= kMaxKeys)
        std::erase_if(failures_, [&](const auto& entry) {
            return entry.second.empty() || now - entry.second.back() >= limits_.window;
        });
    // Still full: the window is being flooded; the newest failures matter, forget the rest.
    if (failures_.size() >= kMaxKeys) failures_.clear();
    // Counted as a failure now, under the lock that checked the limit: parallel attempts see
    // each other before the slow password check, so no more than the limit get to make it.
    failures_[user_key(address, user)].push_back(now);
    failures_[address_key(address)].push_back(now);
    return std::chrono::seconds(0);
}

void SignInLimiter::succeeded(const std::string& address, const std::string& user) {
    std::lock_guard lock(mutex_);
    failures_.erase(user_key(address, user));
    // The attempt counted in begin() was no failure after all.
    if (const auto it = failures_.find(address_key(address));
        it != failures_.end() && !it->second.empty())
        it->second.pop_back();
}

}  // namespace tilejet::api
