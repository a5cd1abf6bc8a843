#pragma once

// HttpServer: HTTP/1.1 on GNU libmicrohttpd, with every resource a client can make it spend
// bounded by design (README.md, "Hostile clients"):
//  - one event-driven network thread (epoll): a slow or idle client costs a socket and a few
//    KB, never a thread;
//  - connections capped in total and per client address; when full, a connection with no
//    request under way is closed for the new one (one kept open after a refusal first, then
//    one that never sent a whole request, then a keep-alive one between good answers; oldest
//    first), so that a flood from the panel's own address cannot lock the operator out;
//  - deadlines for a request's line and headers (from the connection's start or its previous
//    answer) and for its body, however slowly the bytes trickle in;
//  - 32 KB per connection for the request line and headers (a longer one gets 414 or 431);
//  - bodies bounded per route before they are read (Content-Length) and as they arrive (chunked
//    bodies too), and all bodies in memory at once bounded together;
//  - handlers run on small lanes with bounded queues (router.hpp), full lanes answer 503;
//  - streamed bodies (events) are polled by one thread, never a thread per stream.
#include <microhttpd.h>

#include <array>
#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "router.hpp"
#include "tilejet/api/access.hpp"
#include "work_lane.hpp"

namespace tilejet::api {

class HttpServer {
  public:
    struct Hooks {
        // Before routing, with the headers only: true when it answered (the body is not read).
        std::function<bool(const HttpRequest&, HttpResponse&)> before;
        // Headers every answer carries.
        std::function<void(HttpResponse&)> after;
    };
    // Listens at once (port 0: the kernel picks); throws naming the address when it cannot.
    HttpServer(const Router& router, Hooks hooks, const ServerLimits& limits,
               const std::string& host, int port);
    // Ends the streams, answers what the lanes hold, then stops.
    ~HttpServer();
    HttpServer(const HttpServer&) = delete;
    HttpServer& operator=(const HttpServer&) = delete;
    int port() const { return port_; }

  private:
    struct Connection;
    struct Exchange;
    struct Stream;
    using Clock = std::chrono::steady_clock;

    // libmicrohttpd's callbacks, through `this` as their closure.
    static MHD_Result accept_cb(void* self, const sockaddr* addr, socklen_t len);
    static void connection_cb(void* self, MHD_Connection* c, void** context,
                              MHD_ConnectionNotificationCode code);
    static MHD_Result request_cb(void* self, MHD_Connection* c, const char* url, const char* method,
                                 const char* version, const char* upload, size_t* upload_size,
                                 void** exchange);
    static void completed_cb(void* self, MHD_Connection* c, void** exchange,
                             MHD_RequestTerminationCode code);
    static ssize_t stream_read_cb(void* stream, uint64_t pos, char* buf, size_t max);
    static void stream_free_cb(void* stream);

    bool accept(const std::string& address);
    MHD_Result on_request(MHD_Connection* c, Exchange& ex, const char* upload, size_t* upload_size);
    void begin(MHD_Connection* c, Exchange& ex);
    MHD_Result answer(MHD_Connection* c, Exchange& ex);
    // A queued request's turn in its lane: its handler, unless its connection was cut meanwhile.
    void run_queued(Exchange& ex);
    // 503: a lane full, or a queued request cut for a newer connection.
    static void refuse_busy(Exchange& ex);
    void run_handler(Exchange& ex);
    void housekeep();
    void enforce_deadlines(Clock::time_point now);
    void feed_streams(bool ending);
    // Closes a connection (of `address`, or of any when empty) that has no request under way,
    // or a flooding client's queued request, the likeliest hostile first; false when there is
    // none.
    bool evict_idle(const std::string& address);

    const Router& router_;
    Hooks hooks_;
    const ServerLimits limits_;
    std::array<std::unique_ptr<WorkLane>, 3> lanes_;  // by Lane

    std::mutex connections_mutex_;
    std::vector<Connection*> connections_;  // owned through their socket contexts

    std::mutex streams_mutex_;
    std::vector<std::shared_ptr<Stream>> streams_;

    std::atomic<std::size_t> body_bytes_{0};  // bodies held in memory, all connections
    std::atomic<bool> stopping_{false};
    MHD_Daemon* daemon_ = nullptr;
    int port_ = 0;
    std::thread housekeeper_;
};

}  // namespace tilejet::api
