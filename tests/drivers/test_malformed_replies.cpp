// A fake PLC on loopback that answers the client's sync reads properly and then misbehaves:
// garbage, short replies, wrong transaction ids, exception codes, silence. Every case must end
// in a clear error naming the register, within the timeout, never a crash or a hang.

#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <catch2/catch.hpp>
#include <fstream>
#include <functional>
#include <thread>

#include "linesim_process.hpp"
#include "tilejet/drivers/modbus/modbus_line_control.hpp"

using namespace tilejet;
using namespace std::chrono_literals;
using Catch::Matchers::Contains;

namespace {

// What the fake PLC does with the request that follows the connect-time sync.
enum class Misbehaviour {
    garbage,
    short_then_close,
    short_then_silence,
    silence,
    wrong_transaction,
    wrong_count,
    exception_illegal_address,
    exception_busy
};

std::string mbap(const std::string& request, const std::string& pdu) {
    std::string r = request.substr(0, 4);  // transaction id, protocol id
    r += char((pdu.size() + 1) >> 8);
    r += char((pdu.size() + 1) & 0xff);
    r += request[6];  // unit id
    return r + pdu;
}

// A correct reply of zeros to a read (03/04) or an echo to a write (06).
std::string valid_reply(const std::string& req) {
    const auto function = std::uint8_t(req[7]);
    if (function == 6) return mbap(req, req.substr(7, 5));
    const int count = (std::uint8_t(req[10]) << 8) | std::uint8_t(req[11]);
    std::string pdu{char(function), char(2 * count)};
    pdu += std::string(size_t(2 * count), '\0');
    return mbap(req, pdu);
}

class FakePlc {
  public:
    explicit FakePlc(Misbehaviour how) : how_(how) {
        listen_ = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
        sockaddr_in a{};
        a.sin_family = AF_INET;
        a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        a.sin_port = 0;  // the kernel picks a free port
        REQUIRE(bind(listen_, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0);
        REQUIRE(listen(listen_, 4) == 0);
        socklen_t length = sizeof a;
        getsockname(listen_, reinterpret_cast<sockaddr*>(&a), &length);
        port_ = ntohs(a.sin_port);
        thread_ = std::thread([this] { serve(); });
    }
    ~FakePlc() {
        stop_ = true;
        thread_.join();
        close(listen_);
    }
    int port() const { return port_; }

  private:
    bool wait_readable(int fd) {
        while (!stop_) {
            pollfd p{fd, POLLIN, 0};
            if (poll(&p, 1, 20) > 0) return true;
        }
        return false;
    }

    void serve() {
        while (wait_readable(listen_)) {
            const int fd = accept(listen_, nullptr, nullptr);
            if (fd < 0) continue;
            int served = 0;
            while (wait_readable(fd)) {
                char buffer[260];
                const ssize_t n = recv(fd, buffer, sizeof buffer, 0);
                if (n < 12) break;
                const std::string req(buffer, size_t(n));
                // The first two requests are the client's sync reads after connecting.
                if (served++ < 2) {
                    send_all(fd, valid_reply(req));
                    continue;
                }
                if (!misbehave(fd, req)) break;
            }
            close(fd);
        }
    }

    static void send_all(int fd, const std::string& bytes) {
        [[maybe_unused]] ssize_t n = send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL);
    }

    // False: close the connection.
    bool misbehave(int fd, const std::string& req) {
        const std::string good = valid_reply(req);
        switch (how_) {
            case Misbehaviour::garbage:
                send_all(fd, std::string("\xde\xad\xbe\xef\x13\x37\x00\xff\xfe\x01\x02\x03", 12));
                return true;
            case Misbehaviour::short_then_close:
                send_all(fd, good.substr(0, 5));
                return false;
            case Misbehaviour::short_then_silence:
                send_all(fd, good.substr(0, 8));
                return true;
            case Misbehaviour::silence:
                return true;
            case Misbehaviour::wrong_transaction: {
                std::string r = good;
                r[1] = char(r[1] + 1);
                send_all(fd, r);
                return true;
            }
            case Misbehaviour::wrong_count: {  // says 2 registers when 1 was asked
                send_all(fd, mbap(req, std::string{req[7], 4, 0, 1, 0, 2}));
                return true;
            }
            case Misbehaviour::exception_illegal_address:
                send_all(fd, mbap(req, std::string{char(req[7] | 0x80), 2}));
                return true;
            case Misbehaviour::exception_busy:
                send_all(fd, mbap(req, std::string{char(req[7] | 0x80), 6}));
                return true;
        }
        return false;
    }

    Misbehaviour how_;
    int listen_ = -1;
    int port_ = 0;
    std::atomic<bool> stop_{false};
    std::thread thread_;
};

drivers::ModbusLineControl client(int port) {
    drivers::ModbusConfig config;
    config.host = "127.0.0.1";
    config.port = port;
    config.response_timeout = 150ms;
    return drivers::ModbusLineControl(
        config, drivers::load_register_map(TILEJET_SOURCE_DIR "/config/registers.toml"));
}

// Runs `f`, which must throw E; returns the message and checks it took less than `bound`.
template <class E>
std::string error_of(const std::function<void()>& f, std::chrono::milliseconds bound) {
    const auto t0 = std::chrono::steady_clock::now();
    std::string message;
    try {
        f();
        FAIL("no error");
    } catch (const E& e) {
        message = e.what();
    }
    CHECK(std::chrono::steady_clock::now() - t0 < bound);
    return message;
}

}  // namespace

TEST_CASE("malformed replies are link errors naming the register", "[drivers][modbus][malformed]") {
    const auto how = GENERATE(Misbehaviour::garbage, Misbehaviour::short_then_close,
                              Misbehaviour::short_then_silence, Misbehaviour::silence,
                              Misbehaviour::wrong_transaction, Misbehaviour::wrong_count);
    CAPTURE(int(how));
    FakePlc plc(how);
    auto line = client(plc.port());
    const auto message = error_of<drivers::LinkError>([&] { line.read("fault_code"); }, 1000ms);
    CHECK_THAT(message, Contains("reading input register 2 'fault_code'"));
    CHECK_THAT(message, Contains("tcp 127.0.0.1:" + std::to_string(plc.port())));
    CHECK_FALSE(line.connected());  // a fresh context next time
}

TEST_CASE("exception replies are register errors naming the register and the code",
          "[drivers][modbus][malformed]") {
    SECTION("illegal data address") {
        FakePlc plc(Misbehaviour::exception_illegal_address);
        auto line = client(plc.port());
        const auto message =
            error_of<drivers::RegisterError>([&] { line.write("speed_setpoint", 5); }, 1000ms);
        CHECK_THAT(message, Contains("writing 5 to holding register 100 'speed_setpoint'"));
        CHECK_THAT(message, Contains("exception 2"));
        CHECK_THAT(message, Contains("Illegal data address"));
        CHECK(line.connected());  // the link itself is fine
    }
    SECTION("server busy") {
        FakePlc plc(Misbehaviour::exception_busy);
        auto line = client(plc.port());
        const auto message = error_of<drivers::RegisterError>([&] { line.read("estop"); }, 1000ms);
        CHECK_THAT(message, Contains("input register 6 'estop'"));
        CHECK_THAT(message, Contains("exception 6"));
    }
}

TEST_CASE("an illegal address on the real simulator names the register",
          "[drivers][modbus][malformed]") {
    // The client believes in one more input register (address 7) than the simulator serves.
    test::LinesimProcess sim;
    test::TempDir dir;
    const std::string path = (dir.path() / "registers.toml").string();
    {
        std::ifstream in(TILEJET_SOURCE_DIR "/config/registers.toml");
        std::ofstream out(path);
        out << in.rdbuf() << "\n[[register]]\nname = \"glaze_level\"\ntable = \"input\"\n"
            << "address = 7\ntype = \"u16\"\nmeaning = \"not on this PLC\"\n";
    }
    drivers::ModbusLineControl line(sim.config().modbus, drivers::load_register_map(path));
    // The connect-time sync reads the whole input block and is refused ...
    const auto sync = error_of<drivers::RegisterError>([&] { line.read_state(); }, 1000ms);
    CHECK_THAT(sync, Contains("input registers 0..7") && Contains("glaze_level") &&
                         Contains("exception 2"));
    // ... and the single register is named on its own.
    const auto one = error_of<drivers::RegisterError>([&] { line.read("glaze_level"); }, 1000ms);
    CHECK_THAT(one, Contains("reading input register 7 'glaze_level'") &&
                        Contains("Illegal data address"));
    // Registers the simulator has still read fine on the same link.
    CHECK(line.read("speed_setpoint") == 1000);
}
