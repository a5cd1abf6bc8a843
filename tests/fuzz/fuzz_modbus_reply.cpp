// Modbus replies: a PLC on loopback answers the client's first requests properly (0-3 of them:
// the connect-time sync reads the input and holding blocks) and then sends the fuzzer's bytes as
// the reply to the next one, optionally with a correct MBAP header so the bytes get past
// libmodbus's framing into the register decoding. Any reply must end in a value or a
// LinkError/RegisterError, never a crash, a hang or a leak.
//
// Input: byte 0 = which call (read_state, read_all, read, write) and how many valid replies come
// first; byte 1 bit 0 = patch the MBAP header; the rest = the reply.
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

#include "tilejet/drivers/modbus/modbus_line_control.hpp"

using namespace tilejet;

namespace {

std::string valid_reply(const std::string& req) {
    std::string r = req.substr(0, 7);
    const auto function = std::uint8_t(req[7]);
    std::string pdu;
    if (function == 6 || function == 16) {
        pdu = req.substr(7, 5);
    } else {
        const int count = (std::uint8_t(req[10]) << 8) | std::uint8_t(req[11]);
        pdu = std::string{char(function), char(2 * count)} + std::string(size_t(2 * count), '\1');
    }
    r[4] = char((pdu.size() + 1) >> 8);
    r[5] = char((pdu.size() + 1) & 0xff);
    return r + pdu;
}

// One connection at a time: the fuzz loop connects, the server plays the current script.
class ScriptedPlc {
  public:
    ScriptedPlc() {
        listen_ = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
        const int one = 1;
        setsockopt(listen_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
        sockaddr_in a{};
        a.sin_family = AF_INET;
        a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        bind(listen_, reinterpret_cast<sockaddr*>(&a), sizeof a);
        listen(listen_, 8);
        socklen_t length = sizeof a;
        getsockname(listen_, reinterpret_cast<sockaddr*>(&a), &length);
        port_ = ntohs(a.sin_port);
        std::thread([this] { serve(); }).detach();
    }
    int port() const { return port_; }

    void set_script(int valid_first, bool patch_header, std::string reply) {
        std::lock_guard lock(mutex_);
        valid_first_ = valid_first;
        patch_header_ = patch_header;
        reply_ = std::move(reply);
    }

  private:
    static bool readable(int fd, int ms) {
        pollfd p{fd, POLLIN, 0};
        return poll(&p, 1, ms) > 0;
    }

    void serve() {
        while (true) {
            const int fd = accept(listen_, nullptr, nullptr);
            if (fd < 0) continue;
            int served = 0;
            while (readable(fd, 100)) {
                char buffer[300];
                const ssize_t n = recv(fd, buffer, sizeof buffer, 0);
                if (n < 12) break;
                const std::string req(buffer, size_t(n));
                std::string out;
                {
                    std::lock_guard lock(mutex_);
                    if (served++ < valid_first_) {
                        out = valid_reply(req);
                    } else {
                        out = reply_;
                        if (patch_header_ && out.size() >= 7) {
                            out.replace(0, 4, req.substr(0, 4));
                            out[4] = char((out.size() - 6) >> 8);
                            out[5] = char((out.size() - 6) & 0xff);
                        }
                    }
                }
                [[maybe_unused]] ssize_t sent = send(fd, out.data(), out.size(), MSG_NOSIGNAL);
            }
            close(fd);
        }
    }

    int listen_ = -1;
    int port_ = 0;
    std::mutex mutex_;
    int valid_first_ = 0;
    bool patch_header_ = false;
    std::string reply_;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static ScriptedPlc plc;
    static const drivers::RegisterMap registers =
        drivers::load_register_map(TILEJET_SOURCE_DIR "/config/registers.toml");
    if (size < 2) return 0;
    const int call = data[0] & 3;
    plc.set_script((data[0] >> 2) & 3, data[1] & 1,
                   std::string(reinterpret_cast<const char*>(data + 2), size - 2));
    drivers::ModbusConfig config;
    config.host = "127.0.0.1";
    config.port = plc.port();
    config.response_timeout = std::chrono::milliseconds(30);
    try {
        drivers::ModbusLineControl line(config, registers);
        switch (call) {
            case 0:
                line.read_state();
                break;
            case 1:
                line.read_all();
                break;
            case 2:
                line.read("tile_counter");
                break;
            default:
                line.write("speed_setpoint", 700);
                break;
        }
    } catch (const drivers::LinkError&) {
    } catch (const drivers::RegisterError&) {
    }
    return 0;
}
