#include "print_heads.hpp"

#include <fcntl.h>
#include <openssl/evp.h>
#include <sys/socket.h>
#include <sys/uio.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "../unix_socket.hpp"

namespace tilejet::linesim {

namespace {

// Separations of one tile: 4 inks at 8 bit for a 1.2 x 1.2 m tile at 720 dpi is ~4.5 GB; the
// largest format lines print today stay far below this bound.
constexpr size_t kMaxTileBytes = size_t(1) << 30;
constexpr size_t kHeaderRead = 4096;

// Whether the peer has not closed its end (nothing waiting to be read counts as open).
bool still_open(int fd) {
    char byte;
    const ssize_t n = ::recv(fd, &byte, 1, MSG_PEEK | MSG_DONTWAIT);
    return n > 0 || (n < 0 && (errno == EAGAIN || errno == EINTR));
}
constexpr size_t kScratchBytes = size_t(1) << 20;
// Tiles the print journal remembers: far more than a buffer holds, so that any tile the daemon
// can still be unsure of is in it.
constexpr size_t kJournalTiles = 4096;

std::string sha256_hex(EVP_MD_CTX& digest) {
    unsigned char bytes[EVP_MAX_MD_SIZE];
    unsigned int length = 0;
    EVP_DigestFinal_ex(&digest, bytes, &length);
    static const char* hex = "0123456789abcdef";
    std::string out;
    for (unsigned i = 0; i < length; ++i) {
        out += hex[bytes[i] >> 4];
        out += hex[bytes[i] & 15];
    }
    return out;
}

// The wall-clock time of a CLOCK_MONOTONIC instant, ISO 8601 UTC with milliseconds.
std::string wall_time(ns monotonic) {
    const auto now_mono = std::chrono::steady_clock::now().time_since_epoch();
    const auto wall =
        std::chrono::system_clock::now() -
        std::chrono::duration_cast<std::chrono::system_clock::duration>(now_mono - monotonic);
    const std::time_t seconds = std::chrono::system_clock::to_time_t(wall);
    const auto ms =
        std::chrono::duration_cast<std::chrono::milliseconds>(wall.time_since_epoch()).count() %
        1000;
    std::tm tm{};
    gmtime_r(&seconds, &tm);
    char text[40];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &tm);
    char out[48];
    std::snprintf(out, sizeof out, "%s.%03dZ", text, int(ms));
    return out;
}

}  // namespace

PrintHeads::PrintHeads(std::string path, int buffer_tiles, bool checksums,
                       const std::string& log_path)
    : path_(std::move(path)),
      capacity_(size_t(buffer_tiles)),
      checksums_(checksums),
      scratch_(kScratchBytes) {
    listen_fd_ = drivers::sim::listen_unix(path_);
    devnull_ = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (devnull_ < 0) throw std::runtime_error("cannot open /dev/null");
    if (!log_path.empty()) {
        log_.open(log_path, std::ios::app);
        if (!log_) throw std::runtime_error("cannot open print log " + log_path);
    }
}

PrintHeads::~PrintHeads() {
    for (const Client& c : clients_)
        ::close(c.peer.fd);
    ::close(listen_fd_);
    ::close(devnull_);
    ::unlink(path_.c_str());
}

void PrintHeads::PipeEnd::reset(int fd) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = fd;
}

std::vector<int> PrintHeads::fds() const {
    std::vector<int> fds{listen_fd_};
    for (const Client& c : clients_) {
        fds.push_back(c.peer.fd);
        if (c.in_tile && c.pipe.fd() >= 0) fds.push_back(c.pipe.fd());
    }
    return fds;
}

void PrintHeads::on_readable(int fd, ns now) {
    if (fd == listen_fd_) {
        const int client = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
        if (client >= 0) {
            Client c;
            c.peer.fd = client;
            clients_.push_back(std::move(c));
        }
        return;
    }
    auto it = std::find_if(clients_.begin(), clients_.end(),
                           [fd](const Client& c) { return c.peer.fd == fd || c.pipe.fd() == fd; });
    if (it == clients_.end()) return;
    // Separations sent on the socket itself are read by serve(), into the hash and no further.
    const bool tile_bytes_on_socket = it->in_tile && it->pipe.fd() < 0;
    const bool open = fd != it->peer.fd || tile_bytes_on_socket || read_socket(*it);
    if (!serve(*it, now) || !open) {
        ::close(it->peer.fd);
        clients_.erase(it);
    }
}

bool PrintHeads::serve(Client& c, ns now) {
    while (true) {
        if (!c.in_tile) {
            std::string line;
            if (!c.peer.next_line(line)) return c.peer.in.size() < 4096;
            if (line == "PIPE") {
                if (c.pipe.fd() < 0) {
                    c.peer.send("ERROR PIPE came without a file descriptor\n");
                    return false;
                }
                c.peer.send("PIPE OK\n");
                continue;
            }
            if (line == "HELD?") {
                c.peer.send("HELD " + std::to_string(buffer_.size()) + "\n");
                continue;
            }
            if (line.starts_with("PRINTED? ")) {
                if (!answer_printed(c, line)) return false;
                continue;
            }
            std::istringstream in(line);
            std::string verb;
            long long bytes = -1;
            in >> verb >> c.job >> c.tile >> bytes;
            if (!in || verb != "TILE" || bytes < 0 || size_t(bytes) > kMaxTileBytes) {
                c.peer.send("ERROR malformed tile header '" + line.substr(0, 200) + "'\n");
                return false;
            }
            c.expected = size_t(bytes);
            c.remaining = c.expected;
            c.in_tile = true;
            EVP_DigestInit_ex(c.digest.get(), EVP_sha256(), nullptr);
        }
        if (!receive_separations(c)) return false;
        if (c.remaining > 0) return true;
        c.in_tile = false;
        // Piped separations are the sender's own pages (vmsplice). A sender that gave up on this
        // tile closed the connection before it reused them, so only while it is still open are
        // the bytes read the ones it sent.
        if (c.pipe.fd() >= 0 && !still_open(c.peer.fd)) return false;
        if (buffer_.size() >= capacity_) {
            c.peer.send("FULL\n");
        } else {
            buffer_.push_back(
                {c.job, c.tile, c.expected, checksums_ ? sha256_hex(*c.digest) : "", now});
            c.peer.send("QUEUED " + std::to_string(buffer_.size()) + "\n");
        }
    }
}

// Hashes the separations as they come instead of keeping them: a 600 x 600 mm tile at 360 dpi
// is 289 MB, and hashing it in one go after the last byte would stall the conveyor's clock.
bool PrintHeads::receive_separations(Client& c) {
    const bool piped = c.pipe.fd() >= 0;
    if (!piped) {  // what came on the socket behind the header
        const size_t buffered = std::min(c.peer.in.size(), c.remaining);
        if (checksums_) EVP_DigestUpdate(c.digest.get(), c.peer.in.data(), buffered);
        c.peer.in.erase(0, buffered);
        c.remaining -= buffered;
    }
    while (c.remaining > 0) {
        const size_t want = std::min(scratch_.size(), c.remaining);
        // Piped bytes the heads need not hash go on to /dev/null by splice, never copied here.
        const ssize_t n = !piped       ? ::recv(c.peer.fd, scratch_.data(), want, MSG_DONTWAIT)
                          : checksums_ ? ::read(c.pipe.fd(), scratch_.data(), want)
                                       : ::splice(c.pipe.fd(), nullptr, devnull_, nullptr,
                                                  c.remaining, SPLICE_F_MOVE | SPLICE_F_NONBLOCK);
        if (n > 0) {
            if (checksums_) EVP_DigestUpdate(c.digest.get(), scratch_.data(), size_t(n));
            c.remaining -= size_t(n);
            continue;
        }
        return n < 0 && (errno == EAGAIN || errno == EINTR);
    }
    return true;
}

bool PrintHeads::read_socket(Client& c) {
    char chunk[kHeaderRead];
    iovec v{chunk, sizeof chunk};
    alignas(cmsghdr) char control[CMSG_SPACE(sizeof(int))];
    msghdr m{};
    m.msg_iov = &v;
    m.msg_iovlen = 1;
    m.msg_control = control;
    m.msg_controllen = sizeof control;
    const ssize_t n = ::recvmsg(c.peer.fd, &m, MSG_DONTWAIT | MSG_CMSG_CLOEXEC);
    if (n == 0) return false;
    if (n < 0) return errno == EAGAIN || errno == EINTR;
    for (cmsghdr* h = CMSG_FIRSTHDR(&m); h; h = CMSG_NXTHDR(&m, h)) {
        if (h->cmsg_level != SOL_SOCKET || h->cmsg_type != SCM_RIGHTS) continue;
        int fd = -1;
        std::memcpy(&fd, CMSG_DATA(h), sizeof fd);
        ::fcntl(fd, F_SETFL, O_NONBLOCK);
        c.pipe.reset(fd);
    }
    c.peer.in.append(chunk, size_t(n));
    return true;
}

bool PrintHeads::answer_printed(Client& c, const std::string& line) {
    std::istringstream in(line.substr(9));
    std::string job, rest;
    std::uint64_t tile = 0;
    in >> job >> tile;
    if (!in || (in >> rest)) {
        c.peer.send("ERROR malformed request '" + line.substr(0, 200) + "'\n");
        return false;
    }
    const bool found =
        std::find(journal_.begin(), journal_.end(), std::pair{job, tile}) != journal_.end();
    // Not in a journal that has forgotten its oldest entries: printed long ago, or never.
    c.peer.send(found ? "PRINTED yes\n" : journal_rolled_ ? "PRINTED unknown\n" : "PRINTED no\n");
    return true;
}

void PrintHeads::tile_arrives(std::uint64_t line_tile, ns at, bool print_enable, bool head_ready) {
    nlohmann::ordered_json j;
    j["time"] = wall_time(at);
    j["line_tile"] = line_tile;
    const bool have = !buffer_.empty() && buffer_.front().received <= at;
    if (have && print_enable && head_ready) {
        const Separations s = buffer_.front();
        buffer_.pop_front();
        j["status"] = "printed";
        j["job"] = s.job;
        j["tile"] = s.tile;
        j["bytes"] = s.bytes;
        if (!s.sha256.empty()) j["sha256"] = s.sha256;
        ++printed_;
        journal_.emplace_back(s.job, s.tile);
        if (journal_.size() > kJournalTiles) {
            journal_.pop_front();
            journal_rolled_ = true;
        }
    } else {
        j["status"] = "missed";
        j["reason"] = !have           ? "no separations before the leading edge"
                      : !print_enable ? "print-enable low"
                                      : "heads not ready";
        ++missed_;
    }
    log(j.dump());
}

void PrintHeads::log(const std::string& json_line) {
    if (!log_.is_open()) return;
    log_ << json_line << '\n';
    log_.flush();  // a test or an operator tails this file while the line runs
}

}  // namespace tilejet::linesim
