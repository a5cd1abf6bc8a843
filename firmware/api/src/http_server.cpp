#include "http_server.hpp"

#include <netdb.h>
#include <sys/ioctl.h>
#include <sys/socket.h>

#include <algorithm>
#include <charconv>
#include <cstring>
#include <stdexcept>
#include <unordered_map>

#include "routes.hpp"
#include "tilejet/api/job_request.hpp"

namespace tilejet::api {

namespace {

// Request line and headers, and libmicrohttpd's own bookkeeping, per connection.
constexpr std::size_t kConnectionMemory = 32 * 1024;
// Paths longer than any route's are refused before a pattern sees them.
constexpr std::size_t kMaxPath = 2048;
// All bodies in memory at once: a few uploads at most.
constexpr std::size_t kBodyBudget = 48 * 1024 * 1024;
// A request answered before its body is read still has this much of the body read and dropped
// first: a client that sends its whole body before it reads (most do) would otherwise find the
// connection reset under the answer. Past this, the answer goes out and the connection closes.
constexpr std::size_t kDrainLimit = 1024 * 1024;
// A stream whose client stopped reading is ended rather than buffered for.
constexpr std::size_t kMaxStreamBacklog = 1024 * 1024;
constexpr auto kHousekeeping = std::chrono::milliseconds(100);
// How long a new connection may wait for its client's first request before it counts as idle:
// on a loaded controller a client can take that long between connect() and send().
constexpr auto kFreshConnection = std::chrono::seconds(1);

// Threads and queue bounds per lane (router.hpp): the sign-in lane hashes passwords one at a
// time, so a flood of sign-ins waits for itself and cannot starve rendering or the status.
struct LaneSize {
    int threads;
    std::size_t queued;
};
// A queued request costs its connection's 32 KB and its body (64 KB at most for these).
constexpr LaneSize kLaneSizes[] = {{4, 256}, {1, 128}, {1, 16}};  // requests, sign_in, pictures

std::string numeric_address(const sockaddr* addr) {
    char host[NI_MAXHOST] = "";
    const socklen_t len = addr->sa_family == AF_INET6 ? sizeof(sockaddr_in6) : sizeof(sockaddr_in);
    if (getnameinfo(addr, len, host, sizeof host, nullptr, 0, NI_NUMERICHOST) != 0) return "?";
    return host;
}

}  // namespace

// One TCP connection: its socket context in libmicrohttpd.
struct HttpServer::Connection {
    MHD_Connection* mhd = nullptr;
    int fd = -1;
    std::string address;
    Clock::time_point opened, phase_start;  // phase: waiting for a request, or reading one
    bool in_request = false;                // headers in, not yet answered
    bool reading_body = false;              // a request whose body is still coming
    bool shut = false;                      // closed by a deadline or for a newer connection
    int answered = 0;                       // requests answered on it so far
    bool last_refused = false;              // the last answer was an error (4xx, 5xx)
    bool waiting_for_lane = false;          // its request queued, the handler not yet started
    std::size_t client = 0;                 // hash of its last request's credentials
};

// One request and its answer: libmicrohttpd's per-request closure.
struct HttpServer::Exchange {
    HttpRequest req;
    HttpResponse res;
    const Route* route = nullptr;
    Connection* connection = nullptr;
    bool answered = false;  // res is ready to send
    bool dispatched = false;
    std::size_t reserved = 0;  // of body_bytes_
    std::size_t drained = 0;   // body bytes dropped after an early answer
    bool queued = false;
};

// A streamed body between its BodyStream (polled by the housekeeper) and the network thread.
struct HttpServer::Stream {
    std::shared_ptr<BodyStream> body;
    MHD_Connection* connection = nullptr;
    HttpServer* server = nullptr;
    std::mutex mutex;
    std::string backlog;
    bool ended = false, suspended = false;
};

HttpServer::HttpServer(const Router& router, Hooks hooks, const ServerLimits& limits,
                       const std::string& host, int port)
    : router_(router), hooks_(std::move(hooks)), limits_(limits) {
    for (size_t i = 0; i < lanes_.size(); ++i)
        lanes_[i] = std::make_unique<WorkLane>(kLaneSizes[i].threads, kLaneSizes[i].queued);

    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    hints.ai_flags = AI_PASSIVE;
    addrinfo* found = nullptr;
    const std::string where = host + ":" + std::to_string(port);
    if (getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &found) != 0 || !found)
        throw std::runtime_error("API: cannot listen on " + where + ": unknown address");
    std::unique_ptr<addrinfo, decltype(&freeaddrinfo)> address(found, freeaddrinfo);

    unsigned flags = MHD_USE_AUTO_INTERNAL_THREAD | MHD_ALLOW_SUSPEND_RESUME;
    if (found->ai_family == AF_INET6) flags |= MHD_USE_IPv6;
    // The hard cap sits above ours: connections closed for newer ones still count until gone.
    const unsigned hard_cap = unsigned(limits_.connections) + 64;
    // Idle connections are closed by enforce_deadlines(); this is libmicrohttpd's own backstop
    // for one that stops reading an answer.
    const unsigned backstop =
        unsigned((limits_.header_timeout + limits_.body_timeout).count()) + 60;
    daemon_ = MHD_start_daemon(
        flags, 0, &HttpServer::accept_cb, this, &HttpServer::request_cb, this, MHD_OPTION_SOCK_ADDR,
        found->ai_addr, MHD_OPTION_LISTENING_ADDRESS_REUSE, 1u, MHD_OPTION_CONNECTION_LIMIT,
        hard_cap, MHD_OPTION_CONNECTION_TIMEOUT, backstop, MHD_OPTION_CONNECTION_MEMORY_LIMIT,
        kConnectionMemory, MHD_OPTION_NOTIFY_COMPLETED, &HttpServer::completed_cb, this,
        MHD_OPTION_NOTIFY_CONNECTION, &HttpServer::connection_cb, this, MHD_OPTION_END);
    if (!daemon_) throw std::runtime_error("API: cannot listen on " + where);
    const MHD_DaemonInfo* info = MHD_get_daemon_info(daemon_, MHD_DAEMON_INFO_BIND_PORT);
    port_ = info ? int(info->port) : port;
    housekeeper_ = std::thread([this] { housekeep(); });
}

HttpServer::~HttpServer() {
    stopping_ = true;
    housekeeper_.join();  // its last turn ended every stream
    // Queued handlers still run and resume their connections: libmicrohttpd must not be
    // stopped with a connection suspended.
    for (auto& lane : lanes_)
        lane->close();
    MHD_stop_daemon(daemon_);
}

// --- connections ---------------------------------------------------------------------------

MHD_Result HttpServer::accept_cb(void* self, const sockaddr* addr, socklen_t) {
    return static_cast<HttpServer*>(self)->accept(numeric_address(addr)) ? MHD_YES : MHD_NO;
}

bool HttpServer::accept(const std::string& address) {
    if (stopping_) return false;
    std::lock_guard lock(connections_mutex_);
    int total = 0, same = 0;
    for (const Connection* c : connections_)
        if (!c->shut) ++total, same += c->address == address;
    if (same >= limits_.connections_per_address && !evict_idle(address)) return false;
    if (total >= limits_.connections && !evict_idle("")) return false;
    return true;
}

bool HttpServer::evict_idle(const std::string& address) {
    const auto now = Clock::now();
    const auto ours = [&](const Connection* c) {
        return !c->shut && (address.empty() || c->address == address);
    };
    // A client (one set of credentials) holding more than a quarter of the slots with requests
    // that wait for a lane is flooding: its queued requests may go for a newer connection,
    // which would otherwise be refused while the lanes catch up (the attack suite's status
    // check was, on a loaded machine, during a flood of one viewer's event-stream requests).
    const int share = (address.empty() ? limits_.connections : limits_.connections_per_address) / 4;
    std::unordered_map<std::size_t, int> queued;
    std::size_t flood = 0;
    int most = 0;
    for (const Connection* c : connections_)
        if (ours(c) && c->waiting_for_lane && ++queued[c->client] > most)
            most = queued[c->client], flood = c->client;
    const bool flooding = most > share;
    const auto flood_request = [&](const Connection* c) {
        return flooding && c->waiting_for_lane && c->client == flood;
    };
    // Who goes first: a connection kept open after a refusal (a flood of requests the API
    // turned down), then one that never sent a whole request for a while (an idle or slow one:
    // the classic flood), then a flooding client's queued request, then a new connection (its
    // client's request may be on its way), then a keep-alive connection between good answers
    // (the operator's panel). The oldest of each first, but the newest of a flood's requests,
    // which would wait the longest.
    const auto rank = [&](const Connection* c) {
        if (c->answered > 0 && c->last_refused) return 0;
        if (flood_request(c)) return 2;
        if (c->answered == 0) return now - c->opened < kFreshConnection ? 3 : 1;
        return 4;
    };
    const auto before = [&](const Connection* a, const Connection* b) {
        const int ra = rank(a), rb = rank(b);
        if (ra != rb) return ra < rb;
        return ra == 2 ? a->phase_start > b->phase_start : a->phase_start < b->phase_start;
    };
    // A connection whose request waits unread in the kernel is a request on its way (the
    // server is busy, not the client idle): it is never cut for a newer one, which would let a
    // burst of connections shut out requests sent before it (the attack suite's status check
    // lost one that way under load). libmicrohttpd reads what comes as soon as it can, so
    // such a wait is short, and the deadlines still apply.
    const auto request_waiting = [](const Connection* c) {
        int unread = 0;
        return !c->in_request && c->fd >= 0 && ::ioctl(c->fd, FIONREAD, &unread) == 0 && unread > 0;
    };
    Connection* victim = nullptr;
    for (Connection* c : connections_)
        // The socket is asked last: only of a connection that would be the victim so far.
        if (ours(c) && (c->reading_body || !c->in_request || flood_request(c)) &&
            (!victim || before(c, victim)) && !request_waiting(c))
            victim = c;
    if (!victim) return false;
    // A queued request so cut is not run (run_queued); its connection closes when resumed.
    victim->shut = true;
    // The socket stays open (libmicrohttpd closes it, seeing the end): no descriptor reuse race.
    ::shutdown(victim->fd, SHUT_RDWR);
    return true;
}

void HttpServer::connection_cb(void* self, MHD_Connection* c, void** context,
                               MHD_ConnectionNotificationCode code) {
    auto& server = *static_cast<HttpServer*>(self);
    std::lock_guard lock(server.connections_mutex_);
    if (code == MHD_CONNECTION_NOTIFY_STARTED) {
        auto conn = std::make_unique<Connection>();
        conn->mhd = c;
        if (const auto* i = MHD_get_connection_info(c, MHD_CONNECTION_INFO_CONNECTION_FD))
            conn->fd = i->connect_fd;
        if (const auto* i = MHD_get_connection_info(c, MHD_CONNECTION_INFO_CLIENT_ADDRESS))
            conn->address = numeric_address(i->client_addr);
        conn->opened = conn->phase_start = Clock::now();
        server.connections_.push_back(conn.get());
        *context = conn.release();
    } else {
        auto* conn = static_cast<Connection*>(*context);
        std::erase(server.connections_, conn);
        delete conn;  // owned by the socket context since STARTED
        *context = nullptr;
    }
}

// --- requests ------------------------------------------------------------------------------

MHD_Result HttpServer::request_cb(void* self, MHD_Connection* c, const char* url,
                                  const char* method, const char*, const char* upload,
                                  size_t* upload_size, void** exchange) {
    auto& server = *static_cast<HttpServer*>(self);
    if (!*exchange) {
        auto ex = std::make_unique<Exchange>();
        ex->req.method = method;
        ex->req.path = url;
        if (const auto* i = MHD_get_connection_info(c, MHD_CONNECTION_INFO_SOCKET_CONTEXT))
            ex->connection = static_cast<Connection*>(i->socket_context);
        *exchange = ex.get();
        server.begin(c, *ex.release());
        return MHD_YES;
    }
    return server.on_request(c, *static_cast<Exchange*>(*exchange), upload, upload_size);
}

void HttpServer::begin(MHD_Connection* c, Exchange& ex) {
    if (ex.connection) {
        std::lock_guard lock(connections_mutex_);
        ex.connection->in_request = ex.connection->reading_body = true;
        ex.connection->phase_start = Clock::now();
        ex.req.remote_addr = ex.connection->address;
    }
    const auto collect = [](void* to, MHD_ValueKind, const char* key, const char* value) {
        static_cast<std::multimap<std::string, std::string, CaseInsensitiveLess>*>(to)->emplace(
            key, value ? value : "");
        return MHD_YES;
    };
    MHD_get_connection_values(c, MHD_HEADER_KIND, collect, &ex.req.headers);
    MHD_get_connection_values(
        c, MHD_GET_ARGUMENT_KIND,
        [](void* to, MHD_ValueKind, const char* key, const char* value) {
            static_cast<std::map<std::string, std::string>*>(to)->emplace(key, value ? value : "");
            return MHD_YES;
        },
        &ex.req.params);

    const auto refuse = [&](int status, const char* field, const std::string& message) {
        reply_error(ex.res, status, field, message);
        ex.answered = true;
    };
    if (ex.req.path.size() > kMaxPath) return refuse(414, "path", "path: too long");
    try {
        if (hooks_.before && hooks_.before(ex.req, ex.res)) {
            ex.answered = true;
            return;
        }
    } catch (const std::exception& e) {
        return refuse(500, "", e.what());
    }
    ex.route = router_.find(ex.req);
    if (!ex.route) return refuse(404, "", "no such resource");
    if (ex.req.has_header("Content-Length")) {
        const std::string text = ex.req.get_header_value("Content-Length");
        std::size_t length = 0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), length);
        // A body too large is a bad request like any other bad field: 400 naming it.
        if (ec != std::errc() || end != text.data() + text.size() || length > ex.route->max_body)
            return refuse(400, "body", "body: too large");
    }
}

MHD_Result HttpServer::on_request(MHD_Connection* c, Exchange& ex, const char* upload,
                                  size_t* upload_size) {
    if (*upload_size > 0) {
        const std::size_t n = *upload_size;
        *upload_size = 0;
        if (ex.answered) {
            ex.drained += n;
            return ex.drained > kDrainLimit ? answer(c, ex) : MHD_YES;
        }
        if (ex.req.body.size() + n > ex.route->max_body) {
            reply_error(ex.res, 400, "body", "body: too large");
            ex.answered = true;
        } else if (body_bytes_.fetch_add(n) + n > kBodyBudget) {
            body_bytes_ -= n;
            reply_error(ex.res, 503, "body", "too many requests in progress; try again");
            ex.answered = true;
        } else {
            ex.reserved += n;
            ex.req.body.append(upload, n);
        }
        if (ex.answered) {  // refused mid-body: what was kept goes, the rest is drained
            body_bytes_ -= ex.reserved;
            ex.reserved = 0;
            std::string().swap(ex.req.body);
        }
        return MHD_YES;
    }
    if (ex.answered) return answer(c, ex);
    if (ex.dispatched) return MHD_YES;  // the handler is still running
    ex.dispatched = true;
    if (ex.connection) {
        std::lock_guard lock(connections_mutex_);
        ex.connection->reading_body = false;
        ex.connection->waiting_for_lane = true;
        ex.connection->client = std::hash<std::string>{}(ex.req.get_header_value("Cookie") + '\n' +
                                                         ex.req.get_header_value("Authorization"));
    }
    // Suspended before the handler can resume it; resumed at once when the lane is full.
    MHD_suspend_connection(c);
    WorkLane& lane = *lanes_[size_t(ex.route->lane)];
    if (!lane.submit([this, c, &ex] {
            run_queued(ex);
            MHD_resume_connection(c);
        })) {
        if (ex.connection) {
            std::lock_guard lock(connections_mutex_);
            ex.connection->waiting_for_lane = false;
        }
        refuse_busy(ex);
        MHD_resume_connection(c);
    }
    return MHD_YES;
}

void HttpServer::run_queued(Exchange& ex) {
    bool cut = false;
    if (ex.connection) {
        std::lock_guard lock(connections_mutex_);
        ex.connection->waiting_for_lane = false;
        cut = ex.connection->shut;
    }
    if (!cut) return run_handler(ex);
    refuse_busy(ex);
}

void HttpServer::refuse_busy(Exchange& ex) {
    reply_error(ex.res, 503, "", "the controller is busy; try again");
    ex.answered = true;
}

void HttpServer::run_handler(Exchange& ex) {
    try {
        ex.route->handler(ex.req, ex.res);
    } catch (const ApiError& e) {
        ex.res = {};
        reply_error(ex.res, e.status(), e.field(), e.what());
    } catch (const std::exception& e) {
        ex.res = {};
        reply_error(ex.res, 500, "", e.what());
    }
    ex.answered = true;
}

MHD_Result HttpServer::answer(MHD_Connection* c, Exchange& ex) {
    if (ex.queued) return MHD_YES;
    ex.queued = true;
    if (hooks_.after) hooks_.after(ex.res);
    MHD_Response* r = nullptr;
    if (ex.res.stream) {
        auto stream = std::make_shared<Stream>();
        stream->body = ex.res.stream;
        stream->connection = c;
        stream->server = this;
        {
            std::lock_guard lock(streams_mutex_);
            streams_.push_back(stream);
        }
        r = MHD_create_response_from_callback(MHD_SIZE_UNKNOWN, 4096, &HttpServer::stream_read_cb,
                                              stream.get(), &HttpServer::stream_free_cb);
        if (!r) stream_free_cb(stream.get());
    } else {
        r = MHD_create_response_from_buffer(ex.res.body.size(), ex.res.body.data(),
                                            MHD_RESPMEM_MUST_COPY);
    }
    if (!r) return MHD_NO;
    for (const auto& [name, value] : ex.res.headers)
        MHD_add_response_header(r, name.c_str(), value.c_str());
    const MHD_Result queued = MHD_queue_response(c, unsigned(ex.res.status), r);
    MHD_destroy_response(r);
    return queued;
}

void HttpServer::completed_cb(void* self, MHD_Connection*, void** exchange,
                              MHD_RequestTerminationCode) {
    auto& server = *static_cast<HttpServer*>(self);
    std::unique_ptr<Exchange> ex(static_cast<Exchange*>(*exchange));
    *exchange = nullptr;
    if (!ex) return;
    server.body_bytes_ -= ex->reserved;
    if (ex->connection) {
        std::lock_guard lock(server.connections_mutex_);
        ex->connection->in_request = ex->connection->reading_body = false;
        ex->connection->phase_start = Clock::now();
        ++ex->connection->answered;
        ex->connection->last_refused = !ex->answered || ex->res.status >= 400;
    }
}

// --- streams -------------------------------------------------------------------------------

ssize_t HttpServer::stream_read_cb(void* p, uint64_t, char* buf, size_t max) {
    auto& s = *static_cast<Stream*>(p);
    std::lock_guard lock(s.mutex);
    if (!s.backlog.empty()) {
        const size_t n = std::min(max, s.backlog.size());
        std::memcpy(buf, s.backlog.data(), n);
        s.backlog.erase(0, n);
        return ssize_t(n);
    }
    // Stopping: the housekeeper's last turn may already have passed this stream by.
    if (s.ended || s.server->stopping_) return MHD_CONTENT_READER_END_OF_STREAM;
    // Nothing to send: out of the event loop until the housekeeper has more (returning 0
    // without suspending would have libmicrohttpd ask again at once, spinning).
    s.suspended = true;
    MHD_suspend_connection(s.connection);
    return 0;
}

void HttpServer::stream_free_cb(void* p) {
    auto* s = static_cast<Stream*>(p);
    std::lock_guard lock(s->server->streams_mutex_);
    std::erase_if(s->server->streams_, [&](const auto& held) { return held.get() == s; });
}

void HttpServer::feed_streams(bool ending) {
    std::vector<std::shared_ptr<Stream>> streams;
    {
        std::lock_guard lock(streams_mutex_);
        streams = streams_;
    }
    for (const auto& s : streams) {
        std::optional<std::string> text;
        if (!ending) {
            try {
                text = s->body->poll();
            } catch (const std::exception&) {
                text.reset();
            }
        }
        std::lock_guard lock(s->mutex);
        if (s->ended) continue;
        if (!text || s->backlog.size() + text->size() > kMaxStreamBacklog) {
            s->ended = true;
            s->backlog.clear();
        } else {
            s->backlog += *text;
        }
        if (s->suspended && (s->ended || !s->backlog.empty())) {
            s->suspended = false;
            MHD_resume_connection(s->connection);
        }
    }
}

// --- housekeeping --------------------------------------------------------------------------

void HttpServer::enforce_deadlines(Clock::time_point now) {
    std::lock_guard lock(connections_mutex_);
    for (Connection* c : connections_) {
        if (c->shut) continue;
        const bool late = c->in_request
                              ? c->reading_body && now - c->phase_start > limits_.body_timeout
                              : now - c->phase_start > limits_.header_timeout;
        if (!late) continue;
        c->shut = true;
        ::shutdown(c->fd, SHUT_RDWR);
    }
}

void HttpServer::housekeep() {
    while (!stopping_) {
        std::this_thread::sleep_for(kHousekeeping);
        enforce_deadlines(Clock::now());
        feed_streams(false);
    }
    feed_streams(true);
}

}  // namespace tilejet::api
