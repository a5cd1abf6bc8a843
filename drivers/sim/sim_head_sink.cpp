#include "tilejet/drivers/sim/sim_head_sink.hpp"

#include <stdexcept>

#include "unix_socket.hpp"

namespace tilejet::drivers::sim {

SimHeadSink::SimHeadSink(std::string socket_path) : path_(std::move(socket_path)) {}

SimHeadSink::~SimHeadSink() = default;

void SimHeadSink::send(const TileSeparations& tile, std::chrono::milliseconds timeout) {
    if (tile.job_id.empty() || tile.job_id.find_first_of(" \t\r\n") != std::string::npos)
        throw std::invalid_argument("sim heads: job id '" + tile.job_id +
                                    "' must be non-empty and without whitespace");
    // Connected lazily and again after an error, so a restarted simulator is picked up.
    if (!socket_)
        socket_ =
            std::make_unique<UnixSocket>(UnixSocket::connect(path_, "sim heads " + path_, timeout));
    try {
        const std::string header = "TILE " + tile.job_id + " " + std::to_string(tile.tile_index) +
                                   " " + std::to_string(tile.bytes.size()) + "\n";
        socket_->send_all(header, timeout);
        socket_->send_all({reinterpret_cast<const char*>(tile.bytes.data()), tile.bytes.size()},
                          timeout);
        auto reply = socket_->read_line(timeout);
        if (!reply)
            throw std::runtime_error("sim heads: no answer for tile " +
                                     std::to_string(tile.tile_index) + " within " +
                                     std::to_string(timeout.count()) + " ms");
        if (reply->starts_with("QUEUED")) return;
        if (*reply == "FULL")
            throw HeadsBusy("sim heads: buffer full, tile " + std::to_string(tile.tile_index) +
                            " not queued");
        throw std::runtime_error("sim heads: tile " + std::to_string(tile.tile_index) + ": " +
                                 *reply);
    } catch (const HeadsBusy&) {
        throw;
    } catch (...) {
        socket_.reset();  // the stream may be mid-tile: start clean next time
        throw;
    }
}

}  // namespace tilejet::drivers::sim
