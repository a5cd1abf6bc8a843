#include "tilejet/drivers/sim/sim_head_sink.hpp"

#include <stdexcept>

#include "byte_pipe.hpp"
#include "unix_socket.hpp"

namespace tilejet::drivers::sim {

namespace {

// The number after `verb` in a reply such as "QUEUED 2".
int count_in(const std::string& reply, std::string_view verb) {
    const std::string count = reply.substr(verb.size());
    if (count.empty() || count.size() > 6 ||
        count.find_first_not_of("0123456789") != std::string::npos)
        throw std::runtime_error("sim heads: malformed reply '" + reply.substr(0, 100) + "'");
    return std::stoi(count);
}

}  // namespace

SimHeadSink::SimHeadSink(std::string socket_path) : path_(std::move(socket_path)) {}

SimHeadSink::~SimHeadSink() = default;

void SimHeadSink::connect(std::chrono::milliseconds timeout) {
    // Lazily, and again after an error, so a restarted simulator is picked up.
    if (socket_) return;
    auto socket =
        std::make_unique<UnixSocket>(UnixSocket::connect(path_, "sim heads " + path_, timeout));
    auto pipe = std::make_unique<BytePipe>();
    socket->send_with_fd("PIPE\n", pipe->read_end(), timeout);
    pipe->close_read_end();
    const auto reply = socket->read_line(timeout);
    if (!reply || *reply != "PIPE OK")
        throw std::runtime_error("sim heads " + path_ + ": the heads did not take the byte pipe" +
                                 (reply ? ": '" + reply->substr(0, 100) + "'" : std::string()));
    socket_ = std::move(socket);
    pipe_ = std::move(pipe);
}

void SimHeadSink::disconnect() {
    socket_.reset();
    pipe_.reset();
}

int SimHeadSink::send(const TileSeparations& tile, std::chrono::milliseconds timeout) {
    if (tile.job_id.empty() || tile.job_id.find_first_of(" \t\r\n") != std::string::npos)
        throw std::invalid_argument("sim heads: job id '" + tile.job_id +
                                    "' must be non-empty and without whitespace");
    connect(timeout);
    try {
        const std::string header = "TILE " + tile.job_id + " " + std::to_string(tile.tile_index) +
                                   " " + std::to_string(tile.bytes.size()) + "\n";
        socket_->send_all(header, timeout);
        pipe_->write_all(tile.bytes, timeout, "sim heads " + path_);
        auto reply = socket_->read_line(timeout);
        if (!reply)
            throw std::runtime_error("sim heads: no answer for tile " +
                                     std::to_string(tile.tile_index) + " within " +
                                     std::to_string(timeout.count()) + " ms");
        if (reply->starts_with("QUEUED ")) return count_in(*reply, "QUEUED ");
        if (*reply == "FULL")
            throw HeadsBusy("sim heads: buffer full, tile " + std::to_string(tile.tile_index) +
                            " not queued");
        throw std::runtime_error("sim heads: tile " + std::to_string(tile.tile_index) + ": " +
                                 *reply);
    } catch (const HeadsBusy&) {
        throw;
    } catch (...) {
        disconnect();
        throw;
    }
}

std::string SimHeadSink::ask(const std::string& request, std::chrono::milliseconds timeout) {
    connect(timeout);
    try {
        socket_->send_all(request + "\n", timeout);
        auto reply = socket_->read_line(timeout);
        if (!reply)
            throw std::runtime_error("sim heads: no answer to " + request + " within " +
                                     std::to_string(timeout.count()) + " ms");
        return *reply;
    } catch (...) {
        disconnect();
        throw;
    }
}

int SimHeadSink::held(std::chrono::milliseconds timeout) {
    const std::string reply = ask("HELD?", timeout);
    try {
        if (!reply.starts_with("HELD "))
            throw std::runtime_error("sim heads: HELD? answered '" + reply.substr(0, 100) + "'");
        return count_in(reply, "HELD ");
    } catch (...) {
        disconnect();  // out of step with the heads: the next exchange starts afresh
        throw;
    }
}

std::optional<bool> SimHeadSink::printed(const std::string& job_id, std::uint64_t tile_index,
                                         std::chrono::milliseconds timeout) {
    if (job_id.empty() || job_id.find_first_of(" \t\r\n") != std::string::npos)
        throw std::invalid_argument("sim heads: job id '" + job_id +
                                    "' must be non-empty and without whitespace");
    const std::string request = "PRINTED? " + job_id + " " + std::to_string(tile_index);
    const std::string reply = ask(request, timeout);
    if (reply == "PRINTED yes") return true;
    if (reply == "PRINTED no") return false;
    if (reply == "PRINTED unknown") return std::nullopt;
    disconnect();  // out of step with the heads: the next exchange starts afresh
    throw std::runtime_error("sim heads: " + request + " answered '" + reply.substr(0, 100) + "'");
}

}  // namespace tilejet::drivers::sim
