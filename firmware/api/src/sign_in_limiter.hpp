#pragma once

// Failed sign-ins counted per user at a client address and per client address over a sliding
// window. While either is over its limit every attempt is refused, the right password
// included: otherwise the limit would only slow a guesser down by the failures it has to make.
// An attempt counts as a failure from the moment it is let through until it succeeds, so that
// the check and the count are one step.
#include <chrono>
#include <deque>
#include <map>
#include <mutex>
#include <string>

#include "tilejet/api/access.hpp"

namespace tilejet::api {

class SignInLimiter {
  public:
    using Clock = std::chrono::steady_clock;
    explicit SignInLimiter(const SignInLimits& limits) : limits_(limits) {}
    // How long until an attempt is allowed; zero when it is now, and the attempt is counted.
    std::chrono::seconds begin(const std::string& address, const std::string& user);
    // The attempt begun was right: the user's failures at that address are forgotten.
    void succeeded(const std::string& address, const std::string& user);

  private:
    std::chrono::seconds wait_for(const std::string& key, int limit, Clock::time_point now);
    SignInLimits limits_;
    std::mutex mutex_;
    std::map<std::string, std::deque<Clock::time_point>> failures_;
};

}  // namespace tilejet::api
