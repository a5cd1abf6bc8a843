#pragma once

// The API's routes: method and path pattern to handler, with what each may take (body size)
// and where it runs (lane). The server asks the router before reading a body, so that a body
// too large for its route, or for no route at all, is never read.
#include <cstddef>
#include <deque>
#include <functional>
#include <regex>
#include <string>
#include <vector>

#include "http_message.hpp"
#include "tilejet/api/job_request.hpp"

namespace tilejet::api {

// Handlers run on a few small pools (lanes) off the network thread, so that slow work of one
// kind (a password hash, a large picture) never holds up the others: /api/status always has a
// lane that sign-ins and pictures cannot fill.
enum class Lane { requests, sign_in, pictures };

// Uploaded maps and profiles are the largest bodies; JSON bodies keep to kMaxBodyBytes.
inline constexpr std::size_t kMaxUploadBody = 16 * 1024 * 1024;

using Handler = std::function<void(const HttpRequest&, HttpResponse&)>;

struct Route {
    std::string method;
    std::regex pattern;
    Handler handler;
    std::size_t max_body = kMaxBodyBytes;
    Lane lane = Lane::requests;
};

class Router {
  public:
    Route& get(const std::string& pattern, Handler h) { return add("GET", pattern, std::move(h)); }
    Route& post(const std::string& pattern, Handler h) {
        return add("POST", pattern, std::move(h));
    }
    Route& put(const std::string& pattern, Handler h) { return add("PUT", pattern, std::move(h)); }
    Route& del(const std::string& pattern, Handler h) {
        return add("DELETE", pattern, std::move(h));
    }
    Route& add(const std::string& method, const std::string& pattern, Handler h);

    // The route for the request's method (HEAD as GET) and path, with req.matches filled; null
    // when none matches.
    const Route* find(HttpRequest& req) const;

  private:
    std::deque<Route> routes_;  // a deque: the Route& add() returns stays valid
};

}  // namespace tilejet::api
