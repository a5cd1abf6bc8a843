// The sim head sink: separations in, the print log out, missed tiles never printed late.

#include <openssl/evp.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstring>
#include <thread>

#include "linesim_process.hpp"
#include "sigpipe_held.hpp"
#include "tilejet/drivers/factory.hpp"
#include "tilejet/drivers/sim/sim_head_sink.hpp"

using namespace tilejet;
using namespace std::chrono_literals;

namespace {

std::string sha256(const std::vector<std::uint8_t>& bytes) {
    unsigned char digest[32];
    unsigned int length = 0;
    EVP_Digest(bytes.data(), bytes.size(), digest, &length, EVP_sha256(), nullptr);
    char hex[65];
    for (int i = 0; i < 32; ++i)
        std::snprintf(hex + 2 * i, 3, "%02x", digest[i]);
    return hex;
}

std::vector<std::uint8_t> separations(size_t size, std::uint8_t seed) {
    std::vector<std::uint8_t> bytes(size);
    for (size_t i = 0; i < size; ++i)
        bytes[i] = std::uint8_t(i * 31 + seed);
    return bytes;
}

}  // namespace

TEST_CASE("separations queued in time are printed, in order, with their hash",
          "[drivers][heads][sim]") {
    test::LinesimOptions o;
    o.speed_mm_s = 1000;  // first tile at the heads after 250 ms, then every 200 ms
    test::LinesimProcess sim(o);
    auto heads = drivers::make_head_sink(sim.config());
    auto gpio = drivers::make_gpio(sim.config());
    gpio->set(drivers::GpioOutput::print_enable, true);
    const auto a = separations(4 * 64 * 64, 1), b = separations(1 << 20, 2);
    // Each answer says how many tiles the heads hold.
    CHECK(heads->send({"job-7", 0, a}, 1s) == 1);
    CHECK(heads->send({"job-7", 1, b}, 1s) == 2);
    // The buffer holds two tiles: a third is refused, not queued.
    const auto c = separations(10, 3);
    CHECK_THROWS_AS(heads->send({"job-7", 2, c}, 1s), drivers::HeadsBusy);
    sim.control("start-conveyor");
    REQUIRE(test::eventually([&] { return sim.print_log().size() >= 3; }, 2s));
    sim.control("stop-conveyor");
    const auto log = sim.print_log();
    CHECK(log[0]["status"] == "printed");
    CHECK(log[0]["job"] == "job-7");
    CHECK(log[0]["tile"] == 0);
    CHECK(log[0]["bytes"] == a.size());
    CHECK(log[0]["sha256"] == sha256(a));
    CHECK(log[1]["tile"] == 1);
    CHECK(log[1]["sha256"] == sha256(b));
    CHECK(log[2]["status"] == "missed");                    // the third tile had nothing queued
    CHECK(log[0]["time"].get<std::string>().size() == 24);  // 2024-01-01T00:00:00.000Z
}

TEST_CASE("separations that arrive after the leading edge are not printed on that tile",
          "[drivers][heads][sim][fault]") {
    test::LinesimOptions o;
    o.speed_mm_s = 1000;  // tiles at the heads at 250, 450, 650 ms after start
    test::LinesimProcess sim(o);
    auto heads = drivers::make_head_sink(sim.config());
    auto gpio = drivers::make_gpio(sim.config());
    gpio->set(drivers::GpioOutput::print_enable, true);
    sim.control("start-conveyor");
    std::this_thread::sleep_for(330ms);  // tile 0 has passed the heads with nothing queued
    const auto late = separations(1000, 9);
    heads->send({"job-late", 0, late}, 1s);
    REQUIRE(test::eventually([&] { return sim.print_log().size() >= 2; }, 2s));
    sim.control("stop-conveyor");
    const auto log = sim.print_log();
    CHECK(log[0]["status"] == "missed");
    CHECK(log[0]["line_tile"] == 0);
    CHECK_FALSE(log[0].contains("sha256"));
    // The late separations go onto the next tile, whole.
    CHECK(log[1]["status"] == "printed");
    CHECK(log[1]["line_tile"] == 1);
    CHECK(log[1]["sha256"] == sha256(late));
}

TEST_CASE("nothing prints while print-enable is low", "[drivers][heads][sim][fault]") {
    test::LinesimOptions o;
    o.speed_mm_s = 2000;
    test::LinesimProcess sim(o);
    auto heads = drivers::make_head_sink(sim.config());
    auto gpio = drivers::make_gpio(sim.config());  // print-enable starts low
    const auto bytes = separations(100, 5);
    heads->send({"job", 0, bytes}, 1s);
    sim.control("start-conveyor");
    REQUIRE(test::eventually([&] { return sim.print_log().size() >= 1; }, 2s));
    sim.control("stop-conveyor");
    const auto log = sim.print_log();
    CHECK(log[0]["status"] == "missed");
    CHECK(log[0]["reason"] == "print-enable low");
}

TEST_CASE("heads that restart lose their buffer, and the next answer shows it",
          "[drivers][heads][sim]") {
    test::LinesimProcess sim;
    auto heads = drivers::make_head_sink(sim.config());
    const auto bytes = separations(1000, 4);
    CHECK(heads->send({"job-1", 0, bytes}, 1s) == 1);
    CHECK(heads->send({"job-1", 1, bytes}, 1s) == 2);
    sim.control("heads-reset");
    CHECK(sim.status()["head_buffer"] == 0);
    CHECK(heads->send({"job-1", 2, bytes}, 1s) == 1);
}

namespace {

// A raw client of the heads' socket, to send a tile in pieces the way a slow link would.
class RawHeadsClient {
  public:
    explicit RawHeadsClient(const std::string& path) : fd_(::socket(AF_UNIX, SOCK_STREAM, 0)) {
        sockaddr_un a{};
        a.sun_family = AF_UNIX;
        path.copy(a.sun_path, sizeof a.sun_path - 1);
        REQUIRE(::connect(fd_, reinterpret_cast<const sockaddr*>(&a), sizeof a) == 0);
    }
    ~RawHeadsClient() { close(); }
    void write(std::string_view bytes) {
        while (!bytes.empty()) {
            const ssize_t n = ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL);
            REQUIRE(n > 0);
            bytes.remove_prefix(size_t(n));
        }
    }
    // `text` with file descriptor `fd` attached, as SimHeadSink passes its pipe.
    void write_with_fd(const std::string& text, int fd) {
        iovec v{const_cast<char*>(text.data()), text.size()};
        alignas(cmsghdr) char control[CMSG_SPACE(sizeof(int))] = {};
        msghdr m{};
        m.msg_iov = &v;
        m.msg_iovlen = 1;
        m.msg_control = control;
        m.msg_controllen = sizeof control;
        cmsghdr* c = CMSG_FIRSTHDR(&m);
        c->cmsg_level = SOL_SOCKET;
        c->cmsg_type = SCM_RIGHTS;
        c->cmsg_len = CMSG_LEN(sizeof(int));
        std::memcpy(CMSG_DATA(c), &fd, sizeof fd);
        REQUIRE(::sendmsg(fd_, &m, MSG_NOSIGNAL) == ssize_t(text.size()));
    }
    // A pipe handed to the heads as SimHeadSink does (PIPE); returns its write end.
    int pass_pipe() {
        int ends[2];
        REQUIRE(::pipe(ends) == 0);
        write_with_fd("PIPE\n", ends[0]);
        ::close(ends[0]);
        REQUIRE(read_line() == "PIPE OK");
        return ends[1];
    }
    std::string read_line() {
        std::string line;
        char c = 0;
        while (::recv(fd_, &c, 1, 0) == 1 && c != '\n')
            line += c;
        return line;
    }
    void close() {
        if (fd_ >= 0) ::close(fd_);
        fd_ = -1;
    }

  private:
    int fd_;
};

std::string_view as_text(const std::vector<std::uint8_t>& bytes) {
    return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
}

}  // namespace

TEST_CASE(
    "separations that come in pieces are hashed whole, and the next header may share a "
    "piece",
    "[drivers][heads][sim]") {
    test::LinesimProcess sim;
    RawHeadsClient client(sim.config().sim.head_socket);
    // Larger than the heads' 1 MB read buffer, and an odd size so no piece lines up with it.
    const auto a = separations((3 << 20) + 12345, 6), b = separations(777, 7);
    const std::string header_a = "TILE job-p 0 " + std::to_string(a.size()) + "\n";
    const std::string header_b = "TILE job-p 1 " + std::to_string(b.size()) + "\n";
    client.write(header_a + std::string(as_text(a).substr(0, 100)));
    std::this_thread::sleep_for(20ms);
    client.write(as_text(a).substr(100, 2 << 20));
    std::this_thread::sleep_for(20ms);
    client.write(std::string(as_text(a).substr(100 + (2 << 20))) + header_b +
                 std::string(as_text(b)));
    CHECK(client.read_line() == "QUEUED 1");
    CHECK(client.read_line() == "QUEUED 2");
    auto gpio = drivers::make_gpio(sim.config());
    gpio->set(drivers::GpioOutput::print_enable, true);
    sim.control("start-conveyor");
    REQUIRE(test::eventually([&] { return sim.print_log().size() >= 2; }, 2s));
    sim.control("stop-conveyor");
    const auto log = sim.print_log();
    CHECK(log[0]["bytes"] == a.size());
    CHECK(log[0]["sha256"] == sha256(a));
    CHECK(log[1]["tile"] == 1);
    CHECK(log[1]["sha256"] == sha256(b));
}

TEST_CASE("a client that closes mid-tile queues nothing", "[drivers][heads][sim][fault]") {
    test::LinesimProcess sim;
    {
        RawHeadsClient client(sim.config().sim.head_socket);
        client.write(std::string("TILE job-c 0 5000\n").append(3000, 'x'));
    }
    auto heads = drivers::make_head_sink(sim.config());
    CHECK(heads->held(1s) == 0);
    const auto bytes = separations(100, 8);
    CHECK(heads->send({"job-c", 1, bytes}, 1s) == 1);
}

TEST_CASE("heads without checksums log the byte count and no hash", "[drivers][heads][sim]") {
    test::LinesimOptions o;
    o.head_checksums = false;
    test::LinesimProcess sim(o);
    auto heads = drivers::make_head_sink(sim.config());
    auto gpio = drivers::make_gpio(sim.config());
    gpio->set(drivers::GpioOutput::print_enable, true);
    const auto bytes = separations(4096, 9);
    CHECK(heads->send({"job-n", 0, bytes}, 1s) == 1);
    sim.control("start-conveyor");
    REQUIRE(test::eventually([&] { return sim.print_log().size() >= 1; }, 2s));
    sim.control("stop-conveyor");
    const auto log = sim.print_log();
    CHECK(log[0]["status"] == "printed");
    CHECK(log[0]["bytes"] == bytes.size());
    CHECK_FALSE(log[0].contains("sha256"));
}

TEST_CASE("PIPE without a file descriptor is refused", "[drivers][heads][sim][fault]") {
    test::LinesimProcess sim;
    RawHeadsClient client(sim.config().sim.head_socket);
    client.write("PIPE\n");
    CHECK(client.read_line().starts_with("ERROR PIPE"));
}

TEST_CASE("a piped tile whose sender hung up before the heads had it all is not queued",
          "[drivers][heads][sim][fault]") {
    test::LinesimProcess sim;
    int feed = -1;
    {
        RawHeadsClient client(sim.config().sim.head_socket);
        feed = client.pass_pipe();
        client.write("TILE job-h 0 5000\n");
        REQUIRE(::write(feed, std::string(3000, 'x').data(), 3000) == 3000);
        std::this_thread::sleep_for(50ms);  // the heads have read the first part
    }
    // The sender gave up: from here on its pages may hold anything. The rest still arrives,
    // unless the heads have closed the pipe already (then the write fails with EPIPE: this
    // process keeps SIGPIPE's default, which killed it here once, and the test with it).
    ssize_t rest = 0;
    int error = 0;
    {
        drivers::sim::SigpipeHeld held;
        rest = ::write(feed, std::string(2000, 'y').data(), 2000);
        error = errno;
        if (rest < 0 && error == EPIPE) held.raised();
    }
    REQUIRE((rest == 2000 || (rest < 0 && error == EPIPE)));
    ::close(feed);
    auto heads = drivers::make_head_sink(sim.config());
    CHECK(heads->held(1s) == 0);
}

TEST_CASE("separations sent through the pipe are hashed whole", "[drivers][heads][sim]") {
    test::LinesimProcess sim;
    RawHeadsClient client(sim.config().sim.head_socket);
    const int feed = client.pass_pipe();
    const auto a = separations((2 << 20) + 3, 10);
    client.write("TILE job-q 4 " + std::to_string(a.size()) + "\n");
    std::thread writer([&] {
        for (size_t done = 0; done < a.size();) {
            const ssize_t n = ::write(feed, a.data() + done, a.size() - done);
            if (n <= 0) break;
            done += size_t(n);
        }
    });
    CHECK(client.read_line() == "QUEUED 1");
    writer.join();
    ::close(feed);
    auto gpio = drivers::make_gpio(sim.config());
    gpio->set(drivers::GpioOutput::print_enable, true);
    sim.control("start-conveyor");
    REQUIRE(test::eventually([&] { return sim.print_log().size() >= 1; }, 2s));
    sim.control("stop-conveyor");
    const auto log = sim.print_log();
    CHECK(log[0]["tile"] == 4);
    CHECK(log[0]["bytes"] == a.size());
    CHECK(log[0]["sha256"] == sha256(a));
}

TEST_CASE("heads that close the pipe mid-tile give an error, not a SIGPIPE",
          "[drivers][heads][sim][fault]") {
    test::LinesimProcess sim;
    auto heads = drivers::make_head_sink(sim.config());
    // Above the heads' 1 GiB limit, so they refuse the header and close while the bytes are
    // still going into the pipe. Untouched anonymous pages cost no memory.
    const size_t size = (size_t(1) << 30) + 4096;
    void* pages =
        ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    REQUIRE(pages != MAP_FAILED);
    const std::span<const std::uint8_t> bytes(static_cast<const std::uint8_t*>(pages), size);
    // This process does not ignore SIGPIPE: the test would die here if the sink let it through.
    CHECK_THROWS_AS(heads->send({"job-big", 0, bytes}, 2s), std::runtime_error);
    ::munmap(pages, size);
    const auto small = separations(100, 11);
    CHECK(heads->send({"job-big", 1, small}, 1s) == 1);  // and the next connection works
}

TEST_CASE("the heads' print journal tells printed tiles from lost ones, through a restart",
          "[drivers][heads][sim]") {
    test::LinesimOptions o;
    o.speed_mm_s = 1000;  // first tile at the heads after 250 ms, then every 200 ms
    test::LinesimProcess sim(o);
    auto heads = drivers::make_head_sink(sim.config());
    auto gpio = drivers::make_gpio(sim.config());
    gpio->set(drivers::GpioOutput::print_enable, true);
    const auto bytes = separations(1000, 4);
    CHECK(heads->send({"job-j", 0, bytes}, 1s) == 1);
    CHECK(heads->send({"job-j", 1, bytes}, 1s) == 2);
    sim.control("start-conveyor");
    REQUIRE(test::eventually([&] { return sim.status()["printed"] == 1; }, 2s));
    sim.control("stop-conveyor");
    sim.control("heads-reset");  // tile 1 is gone unprinted
    CHECK(heads->held(1s) == 0);
    CHECK(heads->printed("job-j", 0, 1s) == std::optional<bool>(true));
    CHECK(heads->printed("job-j", 1, 1s) == std::optional<bool>(false));
    CHECK(heads->printed("job-k", 0, 1s) == std::optional<bool>(false));
    // Asked again on the same connection: the exchange stays in step.
    CHECK(heads->printed("job-j", 0, 1s) == std::optional<bool>(true));
    CHECK_THROWS_AS(heads->printed("job j", 0, 1s), std::invalid_argument);
}

TEST_CASE("a malformed PRINTED? request is refused and the connection closed",
          "[drivers][heads][sim][fault]") {
    test::LinesimProcess sim;
    const std::string request =
        GENERATE(std::string("PRINTED? job-x\n"), std::string("PRINTED? job-x 1 2\n"),
                 std::string("PRINTED? job-x -\n"));
    RawHeadsClient client(sim.config().sim.head_socket);
    client.write(request);
    CHECK(client.read_line().starts_with("ERROR malformed"));
    // The heads stay up for everyone else.
    auto heads = drivers::make_head_sink(sim.config());
    CHECK(heads->held(1s) == 0);
}

namespace {

// Heads that take the pipe and then answer every request with `reply`: what the sink makes of
// a head controller that answers out of turn or with garbage.
class GarbledHeads {
  public:
    GarbledHeads(std::string path, std::string reply) : path_(std::move(path)) {
        listen_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
        sockaddr_un a{};
        a.sun_family = AF_UNIX;
        path_.copy(a.sun_path, sizeof a.sun_path - 1);
        ::unlink(path_.c_str());
        REQUIRE(::bind(listen_, reinterpret_cast<const sockaddr*>(&a), sizeof a) == 0);
        REQUIRE(::listen(listen_, 4) == 0);
        server_ = std::thread([this, reply] {
            const int c = ::accept4(listen_, nullptr, nullptr, SOCK_CLOEXEC);
            if (c < 0) return;
            char buf[256];
            alignas(cmsghdr) char control[CMSG_SPACE(sizeof(int))];
            for (bool first = true;; first = false) {
                iovec v{buf, sizeof buf};
                msghdr m{};
                m.msg_iov = &v;
                m.msg_iovlen = 1;
                m.msg_control = control;
                m.msg_controllen = sizeof control;
                const ssize_t n = ::recvmsg(c, &m, MSG_CMSG_CLOEXEC);
                if (n <= 0) break;
                for (cmsghdr* h = CMSG_FIRSTHDR(&m); h; h = CMSG_NXTHDR(&m, h)) {
                    int fd = -1;
                    std::memcpy(&fd, CMSG_DATA(h), sizeof fd);
                    ::close(fd);
                }
                const std::string answer = first ? "PIPE OK\n" : reply + "\n";
                if (::send(c, answer.data(), answer.size(), MSG_NOSIGNAL) < 0) break;
            }
            ::close(c);
        });
    }
    ~GarbledHeads() {
        ::shutdown(listen_, SHUT_RDWR);
        server_.join();
        ::close(listen_);
        ::unlink(path_.c_str());
    }

  private:
    std::string path_;
    int listen_ = -1;
    std::thread server_;
};

}  // namespace

TEST_CASE("a reply to PRINTED? that is not one is an error naming the request",
          "[drivers][heads][sim][fault]") {
    const std::string reply = GENERATE(std::string("PRINTED maybe"), std::string("HELD 2"),
                                       std::string("PRINTED yes please"), std::string(""));
    test::TempDir dir;
    const std::string path = (dir.path() / "heads.sock").string();
    GarbledHeads server(path, reply);
    drivers::sim::SimHeadSink heads(path);
    try {
        (void)heads.printed("job-g", 3, 1s);
        FAIL("a reply '" << reply << "' was taken");
    } catch (const std::runtime_error& e) {
        CHECK(std::string(e.what()).find("PRINTED? job-g 3") != std::string::npos);
    }
}

TEST_CASE("a reply to HELD? that is not one is an error naming it",
          "[drivers][heads][sim][fault]") {
    const std::string reply =
        GENERATE(std::string("HELD"), std::string("HELD -1"), std::string("PRINTED yes"));
    test::TempDir dir;
    const std::string path = (dir.path() / "heads.sock").string();
    GarbledHeads server(path, reply);
    drivers::sim::SimHeadSink heads(path);
    try {
        (void)heads.held(1s);
        FAIL("a reply '" << reply << "' was taken");
    } catch (const std::runtime_error& e) {
        CHECK(std::string(e.what()).find("HELD") != std::string::npos);
    }
}
