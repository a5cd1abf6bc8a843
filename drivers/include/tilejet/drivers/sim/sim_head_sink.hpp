#pragma once

#include <memory>
#include <string>

#include "tilejet/drivers/head_sink.hpp"

namespace tilejet::drivers::sim {

class UnixSocket;

// HeadSink on the line simulator's heads ([sim] head_socket). Per tile:
//   tilejet -> heads:  TILE <job-id> <tile-index> <byte-count>\n  then the bytes
//   heads -> tilejet:  QUEUED <tiles-in-buffer> | FULL | ERROR <message>
class SimHeadSink : public HeadSink {
  public:
    explicit SimHeadSink(std::string socket_path);
    ~SimHeadSink() override;

    void send(const TileSeparations& tile, std::chrono::milliseconds timeout) override;

  private:
    std::string path_;
    std::unique_ptr<UnixSocket> socket_;
};

}  // namespace tilejet::drivers::sim
