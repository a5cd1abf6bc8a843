#pragma once

// One HTTP request as the routes see it, and the answer they build: plain values, filled and
// sent by HttpServer (http_server.hpp), so that handlers never touch the network library.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace tilejet::api {

// Header names compare without regard to case (RFC 9110 section 5.1).
struct CaseInsensitiveLess {
    bool operator()(const std::string& a, const std::string& b) const;
};

struct HttpRequest {
    std::string method, path;  // path without the query
    std::multimap<std::string, std::string, CaseInsensitiveLess> headers;
    std::map<std::string, std::string> params;  // the query's, decoded
    std::string body;
    std::string remote_addr;           // the client's address, numeric
    std::vector<std::string> matches;  // the route pattern's groups; [0] is the whole path

    bool has_header(const std::string& name) const { return headers.contains(name); }
    // The first value of the header, or "" when there is none.
    std::string get_header_value(const std::string& name) const;
    bool has_param(const std::string& name) const { return params.contains(name); }
    std::string get_param_value(const std::string& name) const;
};

// A body produced over time (server-sent events). The server polls every stream a few times a
// second away from the network thread; poll() returns what to send now (maybe nothing), or
// nullopt when the stream has ended.
class BodyStream {
  public:
    virtual ~BodyStream() = default;
    virtual std::optional<std::string> poll() = 0;
};

struct HttpResponse {
    int status = 200;
    std::vector<std::pair<std::string, std::string>> headers;
    std::string body;
    std::shared_ptr<BodyStream> stream;  // when set, sent instead of body, chunked

    void set_header(const std::string& name, const std::string& value) {
        headers.emplace_back(name, value);
    }
    void set_content(std::string content, const std::string& content_type) {
        body = std::move(content);
        set_header("Content-Type", content_type);
    }
    void set_stream(std::shared_ptr<BodyStream> s, const std::string& content_type) {
        stream = std::move(s);
        set_header("Content-Type", content_type);
    }
};

}  // namespace tilejet::api
