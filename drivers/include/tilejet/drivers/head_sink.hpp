#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>

// HeadSink: where one tile's separations go before its leading edge reaches the heads.
namespace tilejet::drivers {

struct TileSeparations {
    std::string job_id;  // no whitespace (it travels in a line protocol)
    std::uint64_t tile_index = 0;
    // The separations as the heads take them (planar 8-bit contone, one plane per ink); the
    // sink does not look inside.
    std::span<const std::uint8_t> bytes;
};

// The heads' buffer is full: the previous tiles have not been printed yet. Nothing was queued;
// send again after the next tile has passed.
class HeadsBusy : public std::runtime_error {
    using std::runtime_error::runtime_error;
};

class HeadSink {
  public:
    virtual ~HeadSink() = default;

    // Queues the separations for the next tile to reach the heads. The heads print a tile only
    // when its separations were queued before its leading edge arrived; a tile that arrives
    // with nothing queued passes unprinted (logged "missed"), and separations are never
    // printed onto a tile already under the heads. Throws HeadsBusy when the buffer is full,
    // std::runtime_error when the heads cannot be reached within `timeout`. Returns how many
    // tiles the heads hold now, this one included: fewer than the caller sent and saw no tile
    // take means the heads lost their buffer (a head controller that restarted).
    virtual int send(const TileSeparations& tile, std::chrono::milliseconds timeout) = 0;
    // How many tiles the heads hold now; std::runtime_error when they cannot be asked.
    virtual int held(std::chrono::milliseconds timeout) = 0;
    // Whether the heads printed this tile, from their print journal (head controllers log what
    // they fire, for ink use and head life): the only witness that can tell a tile printed
    // while the PLC counter missed it from one the heads lost in a restart. std::nullopt when
    // these heads keep no journal or it no longer reaches back that far; std::runtime_error
    // when they cannot be asked.
    virtual std::optional<bool> printed(const std::string& job_id, std::uint64_t tile_index,
                                        std::chrono::milliseconds timeout) = 0;
};

}  // namespace tilejet::drivers
