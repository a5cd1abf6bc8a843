#pragma once

#include <memory>
#include <string>

#include "tilejet/drivers/head_sink.hpp"

namespace tilejet::drivers::sim {

class UnixSocket;

// HeadSink on the line simulator's heads ([sim] head_socket). Per tile:
//   tilejet -> heads:  TILE <job-id> <tile-index> <byte-count>\n  then the bytes
//   heads -> tilejet:  QUEUED <tiles-in-buffer> | FULL | ERROR <message>
// and on request (HELD?) the tiles in the buffer (HELD <n>).
class SimHeadSink : public HeadSink {
  public:
    explicit SimHeadSink(std::string socket_path);
    ~SimHeadSink() override;

    int send(const TileSeparations& tile, std::chrono::milliseconds timeout) override;
    int held(std::chrono::milliseconds timeout) override;

  private:
    void connect(std::chrono::milliseconds timeout);

    std::string path_;
    std::unique_ptr<UnixSocket> socket_;
};

}  // namespace tilejet::drivers::sim
