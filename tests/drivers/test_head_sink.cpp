// The sim head sink: separations in, the print log out, missed tiles never printed late.

#include <openssl/evp.h>

#include <catch2/catch.hpp>
#include <thread>

#include "linesim_process.hpp"
#include "tilejet/drivers/factory.hpp"

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
