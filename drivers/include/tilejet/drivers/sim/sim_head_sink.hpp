#pragma once

#include <memory>
#include <string>

#include "tilejet/drivers/head_sink.hpp"

namespace tilejet::drivers::sim {

class BytePipe;
class UnixSocket;

// HeadSink on the line simulator's heads ([sim] head_socket). On connecting it hands the heads
// the read end of a pipe (PIPE, answered PIPE OK) that carries the separations. Per tile:
//   tilejet -> heads:  TILE <job-id> <tile-index> <byte-count>\n  then the bytes, on the pipe
//   heads -> tilejet:  QUEUED <tiles-in-buffer> | FULL | ERROR <message>
// and on request the tiles in the buffer (HELD? answered HELD <n>) and whether a tile was printed
// (PRINTED? <job-id> <tile-index> answered PRINTED yes | no | unknown). drivers/sim/PROTOCOLS.md
// has it all.
class SimHeadSink : public HeadSink {
  public:
    explicit SimHeadSink(std::string socket_path);
    ~SimHeadSink() override;

    int send(const TileSeparations& tile, std::chrono::milliseconds timeout) override;
    int held(std::chrono::milliseconds timeout) override;
    std::optional<bool> printed(const std::string& job_id, std::uint64_t tile_index,
                                std::chrono::milliseconds timeout) override;

  private:
    void connect(std::chrono::milliseconds timeout);
    // One request line, one reply line; throws naming the request when no reply comes.
    std::string ask(const std::string& request, std::chrono::milliseconds timeout);

    std::string path_;
    std::unique_ptr<UnixSocket> socket_;
    std::unique_ptr<BytePipe> pipe_;
    // A failed exchange may leave the stream mid-tile: the next one starts on a new connection.
    void disconnect();
};

}  // namespace tilejet::drivers::sim
