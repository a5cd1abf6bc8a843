// The sim GPIO backend (through LatchedGpio, as the daemon gets it from make_gpio) against the
// simulated chip in tilejet-linesim.

#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>

#include "linesim_process.hpp"
#include "tilejet/drivers/factory.hpp"

using namespace tilejet;
using namespace std::chrono_literals;
using drivers::GpioInput;
using drivers::GpioOutput;

namespace {

// Collects events for `duration`.
std::vector<drivers::GpioEvent> collect(drivers::Gpio& gpio, std::chrono::milliseconds duration) {
    std::vector<drivers::GpioEvent> events;
    const auto end = std::chrono::steady_clock::now() + duration;
    while (std::chrono::steady_clock::now() < end)
        if (auto e = gpio.wait_event(20ms)) events.push_back(*e);
    return events;
}

size_t count(const std::vector<drivers::GpioEvent>& events, GpioInput input, bool level) {
    return size_t(std::count_if(events.begin(), events.end(), [&](const auto& e) {
        return e.input == input && e.level == level;
    }));
}

}  // namespace

TEST_CASE("photo-eye edges follow the conveyor, timestamped at the crossing",
          "[drivers][gpio][sim]") {
    test::LinesimOptions o;
    o.speed_mm_s = 2000;  // pitch 200 mm: a tile every 100 ms, covering the eye for 50 ms
    test::LinesimProcess sim(o);
    auto gpio = drivers::make_gpio(sim.config());
    sim.control("start-conveyor");
    const auto events = collect(*gpio, 560ms);
    sim.control("stop-conveyor");
    // Tile 0 reaches the eye (50 mm) after 25 ms, then one tile every 100 ms: 6 in 560 ms.
    const size_t rising = count(events, GpioInput::photo_eye, true);
    CHECK(rising >= 5);
    CHECK(rising <= 6);
    std::vector<std::chrono::nanoseconds> times;
    for (const auto& e : events)
        if (e.input == GpioInput::photo_eye && e.level) times.push_back(e.timestamp);
    // Consecutive leading edges are one pitch apart in time: 100 ms at 2000 mm/s. The timestamps
    // are the crossings, not when the events were read, so they hold to well under a millisecond.
    for (size_t i = 1; i < times.size(); ++i)
        CHECK(std::abs((times[i] - times[i - 1] - 100ms).count()) < 200000);
    // Each tile covers the eye for length / speed = 50 ms.
    for (const auto& e : events)
        if (e.input == GpioInput::photo_eye && !e.level)
            CHECK(std::any_of(times.begin(), times.end(), [&](auto t) {
                return std::abs((e.timestamp - t - 50ms).count()) < 200000;
            }));
}

TEST_CASE("photo-eye glitches do not produce phantom tiles", "[drivers][gpio][sim][fault]") {
    test::LinesimProcess sim;  // debounce 2 ms; conveyor stopped, eye clear
    auto gpio = drivers::make_gpio(sim.config());
    for (int i = 0; i < 5; ++i)
        sim.control("glitch 300");
    auto events = collect(*gpio, 100ms);
    CHECK(count(events, GpioInput::photo_eye, true) == 0);
    CHECK_FALSE(gpio->read(GpioInput::photo_eye));

    // A pulse longer than the debounce time is real: the test can fail.
    sim.control("glitch 10000");
    events = collect(*gpio, 100ms);
    CHECK(count(events, GpioInput::photo_eye, true) == 1);
    CHECK(count(events, GpioInput::photo_eye, false) == 1);
}

TEST_CASE("glitches while tiles pass do not change the tile count", "[drivers][gpio][sim][fault]") {
    test::LinesimOptions o;
    o.speed_mm_s = 2000;
    test::LinesimProcess sim(o);
    auto gpio = drivers::make_gpio(sim.config());
    sim.control("start-conveyor");
    std::thread glitches([&] {
        for (int i = 0; i < 20; ++i) {
            sim.control("glitch 200");
            std::this_thread::sleep_for(17ms);
        }
    });
    const auto events = collect(*gpio, 500ms);
    glitches.join();
    sim.control("stop-conveyor");
    const auto counter = sim.status()["tile_counter"].get<size_t>();
    // Tiles seen by the eye = tiles that reached the heads + those between eye and heads (the
    // heads are 200 mm = one pitch downstream: one tile, or two at the instant of a crossing).
    const size_t rising = count(events, GpioInput::photo_eye, true);
    CHECK(rising >= counter);
    CHECK(rising <= counter + 2);
    CHECK(count(events, GpioInput::photo_eye, false) + 1 >= rising);
}

TEST_CASE("e-stop latches, drops print-enable at once, and needs an acknowledgement",
          "[drivers][gpio][sim][fault]") {
    test::LinesimProcess sim;
    auto gpio = drivers::make_gpio(sim.config());
    gpio->set(GpioOutput::print_enable, true);
    gpio->set(GpioOutput::beacon, true);
    REQUIRE(test::eventually([&] { return sim.status()["print_enable"] == true; }, 1s));
    CHECK(sim.status()["beacon"] == true);

    sim.control("estop on");
    // Print-enable drops on the chip without the daemon doing anything.
    CHECK(test::eventually([&] { return sim.status()["print_enable"] == false; }, 500ms));
    CHECK(gpio->estop_latched());
    CHECK_FALSE(gpio->output(GpioOutput::print_enable));
    CHECK_THROWS_AS(gpio->set(GpioOutput::print_enable, true), drivers::EstopLatched);
    CHECK_THROWS_AS(gpio->acknowledge_estop(), drivers::EstopLatched);  // still pressed

    sim.control("estop off");
    REQUIRE(test::eventually([&] { return !gpio->read(GpioInput::estop); }, 500ms));
    CHECK(gpio->estop_latched());  // released, but still latched
    CHECK_THROWS_AS(gpio->set(GpioOutput::print_enable, true), drivers::EstopLatched);
    CHECK(sim.status()["print_enable"] == false);

    gpio->acknowledge_estop();
    CHECK_FALSE(gpio->estop_latched());
    gpio->set(GpioOutput::print_enable, true);
    CHECK(test::eventually([&] { return sim.status()["print_enable"] == true; }, 500ms));

    // The events tell the same story.
    const auto events = collect(*gpio, 50ms);
    (void)events;
}

TEST_CASE("starting with the e-stop pressed is latched too", "[drivers][gpio][sim][fault]") {
    test::LinesimProcess sim;
    sim.control("estop on");
    auto gpio = drivers::make_gpio(sim.config());
    CHECK(gpio->read(GpioInput::estop));
    CHECK(gpio->estop_latched());
}

TEST_CASE("the simulator's socket folder is private: made 0700, a symlinked one refused",
          "[drivers][sim][security]") {
    test::TempDir dir;
    // The shipped config with the sockets under `folder` and any free Modbus port.
    const auto run_with_sockets_in = [&](const std::filesystem::path& folder) {
        std::ifstream in(TILEJET_SOURCE_DIR "/config/tilejet.toml");
        std::string config((std::istreambuf_iterator<char>(in)), {});
        // Each socket's name, without a folder as shipped, put in `folder`.
        for (const std::string name : {"\"gpio.sock\"", "\"heads.sock\"", "\"control.sock\""}) {
            const size_t at = config.find(name);
            REQUIRE(at != std::string::npos);
            config.insert(at + 1, folder.string() + "/");
        }
        config.replace(config.find("port = 1502"), 11, "port = 0");
        config.replace(config.find("\"registers.toml\""), 16,
                       "\"" TILEJET_SOURCE_DIR "/config/registers.toml\"");
        const auto path = dir.path() / "line.toml";
        std::ofstream(path) << config;
        // Started, it would run until killed: a second is enough to see it listen or refuse.
        const std::string command =
            "timeout 1 " TILEJET_LINESIM " --config " + path.string() + " 2>&1";
        std::string out;
        if (FILE* p = ::popen(command.c_str(), "r")) {
            char buf[512];
            while (size_t n = std::fread(buf, 1, sizeof buf, p))
                out.append(buf, n);
            ::pclose(p);
        }
        return out;
    };
    const auto fresh = dir.path() / "run" / "sim";
    run_with_sockets_in(fresh);
    struct stat st {};
    REQUIRE(::stat(fresh.c_str(), &st) == 0);
    CHECK((st.st_mode & 0777) == 0700);

    const auto open_folder = dir.path() / "open";
    std::filesystem::create_directory(open_folder);
    ::chmod(open_folder.c_str(), 0777);
    run_with_sockets_in(open_folder);
    REQUIRE(::stat(open_folder.c_str(), &st) == 0);
    CHECK((st.st_mode & 0777) == 0700);

    const auto link = dir.path() / "link";
    std::filesystem::create_directory_symlink(open_folder, link);
    const std::string refused = run_with_sockets_in(link);
    CHECK_THAT(refused, Catch::Contains(link.string()) && Catch::Contains("symlink"));
}
