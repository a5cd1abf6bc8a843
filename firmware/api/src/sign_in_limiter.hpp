#pragma once

// Failed sign-ins counted per user and per client address over a sliding window. While either
// is over its limit every attempt is refused, the right password included: otherwise the
// limit would only slow a guesser down by the failures it has to make.
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
    // How long until an attempt is allowed; zero when it is now.
    std::chrono::seconds wait(const std::string& address, const std::string& user);
    void failed(const std::string& address, const std::string& user);
    void succeeded(const std::string& user);

  private:
    std::chrono::seconds wait_for(const std::string& key, int limit, Clock::time_point now);
    SignInLimits limits_;
    std::mutex mutex_;
    std::map<std::string, std::deque<Clock::time_point>> failures_;
};

}  // namespace tilejet::api
