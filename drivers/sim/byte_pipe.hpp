#pragma once

#include <chrono>
#include <cstdint>
#include <span>
#include <string>

// The separations' path to the simulated heads: a pipe whose read end the heads get once per
// connection (SCM_RIGHTS). vmsplice hands the tile's pages to the pipe by reference, where a
// socket copies every byte on both sides: 289 MB a tile, which on a two-core controller would
// take more time than rendering it. Real heads take their data by DMA, which costs the
// controller's cores nothing either.
//
// The pages must not change until the heads have read them. SimHeadSink waits for the heads'
// answer before the caller may reuse them, and after any failure closes the connection, which
// the heads check before they queue a tile.
namespace tilejet::drivers::sim {

class BytePipe {
  public:
    BytePipe();  // throws naming the call that failed
    ~BytePipe();
    BytePipe(const BytePipe&) = delete;
    BytePipe& operator=(const BytePipe&) = delete;

    int read_end() const { return read_; }
    // Once the heads hold the read end: theirs is the only one, so that their end of the pipe
    // closing shows as EPIPE here.
    void close_read_end();
    // All of `bytes` into the pipe within `timeout`; `what` names the peer in errors.
    void write_all(std::span<const std::uint8_t> bytes, std::chrono::milliseconds timeout,
                   const std::string& what);

  private:
    int read_ = -1, write_ = -1;
};

}  // namespace tilejet::drivers::sim
