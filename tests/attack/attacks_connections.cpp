// Traffic that costs an attacker nothing and a thread-per-connection server everything: slow
// senders, idle connections, a viewer's event-stream flood, and blobs too large to buffer.
#include <poll.h>
#include <sys/socket.h>

#include "harness.hpp"

namespace tilejet::attack {

namespace {

void close_all(std::vector<int>& fds) {
    for (int fd : fds)
        if (fd >= 0) ::close(fd);
    fds.clear();
}

// Connections the server has closed (or answered): readable, or hung up.
int closed_by_server(const std::vector<int>& fds) {
    int closed = 0;
    for (int fd : fds) {
        pollfd p{fd, POLLIN, 0};
        if (::poll(&p, 1, 0) == 1) {
            char c;
            if (::recv(fd, &c, 1, MSG_PEEK) <= 0 || (p.revents & (POLLHUP | POLLERR))) ++closed;
        }
    }
    return closed;
}

void slow_senders(Target& t, const Scale& s, Verdict& v) {
    // A sign-in request nobody will ever finish: one byte a second outlasts any per-read timeout.
    const std::string request = "POST /api/session HTTP/1.1\r\nHost: " + t.host_header() +
                                "\r\nContent-Type: application/json\r\nContent-Length: 4096\r\n"
                                "\r\n{\"user\":\"olga\",\"password\":\"" +
                                std::string(4096, 'x');
    std::vector<int> fds;
    for (int i = 0; i < s.slow_senders; ++i)
        // A second try: a full listen queue drops a SYN now and then (cpp-httplib's is 5 long).
        for (int attempt = 0; attempt < 2; ++attempt)
            if (const int fd = connect_loopback(t.port()); fd >= 0) {
                fds.push_back(fd);
                break;
            }
    v.note(std::to_string(fds.size()) + " senders");
    std::vector<bool> open(fds.size(), true);
    const auto end = Clock::now() + s.slow_hold;
    for (std::size_t at = 0; Clock::now() < end; ++at) {
        const auto tick = Clock::now();
        for (std::size_t i = 0; i < fds.size(); ++i)
            if (open[i])
                open[i] = ::send(fds[i], &request[at % request.size()], 1, MSG_NOSIGNAL) == 1;
        std::this_thread::sleep_until(tick + seconds(1));
    }
    int cut = 0;
    for (std::size_t i = 0; i < fds.size(); ++i)
        cut += !open[i] || closed_by_server({fds[i]}) > 0;
    v.note(std::to_string(cut) + " cut off by the server");
    close_all(fds);
}

void idle_flood(Target& t, const Scale& s, Verdict& v) {
    std::vector<int> fds;
    int refused = 0;
    for (int i = 0; i < s.idle_connections; ++i) {
        const int fd = connect_loopback(t.port(), milliseconds(200));
        if (fd >= 0)
            fds.push_back(fd);
        else
            ++refused;
    }
    std::this_thread::sleep_for(s.idle_hold);
    v.note(std::to_string(fds.size()) + " connected, " + std::to_string(refused) +
           " not accepted, " + std::to_string(closed_by_server(fds)) + " closed by the server");
    close_all(fds);
}

// The operator's own event stream, opened while the flood holds: the first line of its answer.
int operator_stream(Target& t) {
    const int fd = connect_loopback(t.port());
    if (fd < 0) return -1;
    std::string request = "GET /api/events HTTP/1.1\r\nHost: " + t.host_header() +
                          "\r\nAccept: text/event-stream\r\n";
    for (const auto& [name, value] : t.operator_session())
        request += name + ": " + value + "\r\n";
    request += "\r\n";
    int status = -1;
    if (send_bytes(fd, request)) status = status_of(read_some(fd, milliseconds(1000)));
    ::close(fd);
    return status;
}

void event_flood(Target& t, const Scale& s, Verdict& v) {
    std::string request = "GET /api/events HTTP/1.1\r\nHost: " + t.host_header() +
                          "\r\nAccept: text/event-stream\r\n";
    for (const auto& [name, value] : t.viewer_session())
        request += name + ": " + value + "\r\n";
    request += "\r\n";
    std::vector<int> fds;
    for (int i = 0; i < s.event_streams; ++i) {
        const int fd = connect_loopback(t.port(), milliseconds(200));
        if (fd < 0) continue;
        if (!send_bytes(fd, request, milliseconds(200))) {
            ::close(fd);
            continue;
        }
        fds.push_back(fd);
    }
    std::this_thread::sleep_for(milliseconds(500));
    // A stream per session, not per server: one viewer's flood leaves the operator's panel live.
    const int own = operator_stream(t);
    v.expect(own == 200, "operator's own event stream answered " +
                             (own < 0 ? std::string("nothing in 1 s") : std::to_string(own)) +
                             " during the flood");
    std::this_thread::sleep_for(s.stream_hold);
    int streaming = 0, refused = 0;
    for (int fd : fds) {
        pollfd p{fd, POLLIN, 0};
        if (::poll(&p, 1, 0) != 1) continue;
        char head[16] = {};
        const ssize_t n = ::recv(fd, head, sizeof head - 1, MSG_PEEK);
        if (n > 0 && status_of(head) == 200) ++streaming;
        if (n > 0 && status_of(head) >= 400) ++refused;
    }
    v.note(std::to_string(fds.size()) + " opened, " + std::to_string(streaming) + " streaming, " +
           std::to_string(refused) + " refused");
    close_all(fds);
}

std::string filler(std::size_t n, char c) {
    return std::string(n, c);
}

void expect_refused(const StreamResult& r, std::size_t total, Verdict& v) {
    v.note(r.how);
    v.expect(!r.finished, "read all " + mib(total) + " without refusing");
    v.expect(r.status < 200 || r.status >= 300, "accepted (" + std::to_string(r.status) + ")");
}

void blob_chunked_body(Target& t, const Scale& s, Verdict& v) {
    // Unauthenticated, so the body limit is all that stands between it and the daemon's memory.
    const std::string head = "POST /api/session HTTP/1.1\r\nHost: " + t.host_header() +
                             "\r\nContent-Type: application/json\r\n"
                             "Transfer-Encoding: chunked\r\n\r\n";
    const std::string chunk = "10000\r\n" + filler(0x10000, 'a') + "\r\n";
    expect_refused(stream_blob(
                       t.port(), head, head.size() + s.body_blob,
                       [&](std::size_t) { return chunk; }, "0\r\n\r\n"),
                   s.body_blob, v);
}

void blob_body(Target& t, const Scale& s, Verdict& v) {
    const std::string head =
        "POST /api/session HTTP/1.1\r\nHost: " + t.host_header() +
        "\r\nContent-Type: application/json\r\nContent-Length: " + std::to_string(s.body_blob) +
        "\r\n\r\n";
    const std::string piece = filler(1 << 16, 'a');
    expect_refused(
        stream_blob(
            t.port(), head, head.size() + s.body_blob, [&](std::size_t) { return piece; }, ""),
        s.body_blob, v);
}

void blob_request_line(Target& t, const Scale& s, Verdict& v) {
    const std::string piece = filler(1 << 16, 'a');
    expect_refused(stream_blob(
                       t.port(), "GET /", s.line_blob, [&](std::size_t) { return piece; },
                       " HTTP/1.1\r\nHost: " + t.host_header() + "\r\n\r\n"),
                   s.line_blob, v);
}

void blob_headers(Target& t, const Scale& s, Verdict& v) {
    // Many ordinary-sized headers: a limit on one line's length alone does not stop these.
    std::string piece;
    for (int i = 0; i < 64; ++i)
        piece += "X-Fill: " + filler(1014, 'a') + "\r\n";
    expect_refused(stream_blob(
                       t.port(), "GET /api/status HTTP/1.1\r\nHost: " + t.host_header() + "\r\n",
                       s.line_blob, [&](std::size_t) { return piece; }, "\r\n"),
                   s.line_blob, v);
}

}  // namespace

std::vector<Attack> connection_attacks() {
    return {{"slow-senders", slow_senders},
            {"idle-flood", idle_flood},
            {"event-stream-flood", event_flood},
            {"blob-chunked-body", blob_chunked_body},
            {"blob-body", blob_body},
            {"blob-request-line", blob_request_line},
            {"blob-headers", blob_headers}};
}

}  // namespace tilejet::attack
