#pragma once

#include <openssl/evp.h>

#include <cstdint>
#include <deque>
#include <fstream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "conveyor.hpp"
#include "peer.hpp"

// The simulated print heads: a small buffer of tiles' separations, fed over a Unix socket, and
// fired when a tile's leading edge arrives. The print log gets one JSON line per tile that
// reached the heads, printed or missed.
namespace tilejet::linesim {

class PrintHeads {
  public:
    PrintHeads(std::string path, int buffer_tiles, bool checksums, const std::string& log_path);
    ~PrintHeads();

    std::vector<int> fds() const;
    void on_readable(int fd, ns now);

    // Tile `line_tile`'s leading edge reached the heads at `at`. It is printed only with
    // separations received before `at`; otherwise it is logged missed and whatever arrives
    // later waits for the next tile.
    void tile_arrives(std::uint64_t line_tile, ns at, bool print_enable, bool head_ready);

    size_t buffered() const { return buffer_.size(); }
    // A head controller that restarted: every buffered tile is gone. The print journal is
    // kept (controllers keep it with their print counts, through restarts).
    void reset_buffer() { buffer_.clear(); }
    std::uint64_t printed() const { return printed_; }
    std::uint64_t missed() const { return missed_; }

  private:
    struct Separations {
        std::string job;
        std::uint64_t tile;
        size_t bytes;
        std::string sha256;
        ns received;
    };
    // The read end of a client's byte pipe, closed with the client.
    class PipeEnd {
      public:
        PipeEnd() = default;
        ~PipeEnd() { reset(); }
        PipeEnd(PipeEnd&& o) noexcept : fd_(std::exchange(o.fd_, -1)) {}
        PipeEnd& operator=(PipeEnd&& o) noexcept {
            if (this != &o) reset(std::exchange(o.fd_, -1));
            return *this;
        }
        void reset(int fd = -1);
        int fd() const { return fd_; }

      private:
        int fd_ = -1;
    };
    struct Client {
        Peer peer;
        PipeEnd pipe;  // separations come here once the client has passed one (PIPE)
        std::string job;
        std::uint64_t tile = 0;
        size_t expected = 0, remaining = 0;
        bool in_tile = false;
        std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> digest{EVP_MD_CTX_new(),
                                                                       &EVP_MD_CTX_free};
    };

    // False when the client sent something it cannot recover from (closed then).
    bool serve(Client& client, ns now);
    // PRINTED? <job> <tile>: whether the journal has it. False for a malformed request.
    bool answer_printed(Client& client, const std::string& line);
    // False when the client closed mid-tile.
    bool receive_separations(Client& client);
    // What came on the client's socket: lines, and a pipe passed with them. False once closed.
    bool read_socket(Client& client);
    void log(const std::string& json_line);

    std::string path_;
    int listen_fd_ = -1;
    size_t capacity_;
    bool checksums_;
    std::vector<Client> clients_;
    std::deque<Separations> buffer_;
    // The last kJournalTiles tiles printed, oldest first: PRINTED? asks it.
    std::deque<std::pair<std::string, std::uint64_t>> journal_;
    bool journal_rolled_ = false;  // it has forgotten some
    std::ofstream log_;
    std::vector<char> scratch_;
    int devnull_ = -1;
    std::uint64_t printed_ = 0, missed_ = 0;
};

}  // namespace tilejet::linesim
