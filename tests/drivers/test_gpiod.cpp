// The libgpiod backend: what can be checked without hardware, and on a gpio-sim chip made
// through configfs when the kernel has one (a skip that says so when it has not).

#include <gpiod.h>
#include <time.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "tilejet/drivers/factory.hpp"
#include "tilejet/drivers/gpiod/gpiod_lines.hpp"

using namespace tilejet;
using Catch::Matchers::Contains;
using drivers::gpiod::GpiodLines;

TEST_CASE("kernel line events become edges with the kernel's timestamp", "[drivers][gpiod]") {
    const timespec ts{1234, 567890123};
    const auto rising = GpiodLines::edge_from_event(drivers::GpioInput::photo_eye,
                                                    GPIOD_LINE_EVENT_RISING_EDGE, ts);
    CHECK(rising.input == drivers::GpioInput::photo_eye);
    CHECK(rising.level);
    CHECK(rising.timestamp.count() == 1234567890123LL);
    const auto falling =
        GpiodLines::edge_from_event(drivers::GpioInput::estop, GPIOD_LINE_EVENT_FALLING_EDGE, ts);
    CHECK_FALSE(falling.level);
    CHECK_THROWS_WITH(GpiodLines::edge_from_event(drivers::GpioInput::estop, 99, ts),
                      Contains("unknown event type 99"));
}

TEST_CASE("a chip that does not exist is a clear error naming the config key", "[drivers][gpiod]") {
    drivers::GpioConfig config;
    config.backend = "gpiod";
    config.chip = "tilejet-no-such-chip";
    CHECK_THROWS_WITH(GpiodLines(config),
                      Contains("[gpio] chip") && Contains("'tilejet-no-such-chip'"));
}

namespace {

void write_file(const std::filesystem::path& path, const std::string& text) {
    std::ofstream out(path);
    out << text;
    out.close();
    if (!out) throw std::runtime_error("cannot write " + path.string());
}

std::string read_file(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::string text;
    std::getline(in, text);
    return text;
}

// A gpio-sim chip made through configfs (kernel docs: admin-guide/gpio/gpio-sim) with the line
// names of config/tilejet.toml, taken down again by the destructor. Inputs are driven from the
// "outside" through each line's sysfs `pull` attribute; outputs are read back from `value`.
class GpioSimChip {
  public:
    static constexpr const char* kRoot = "/sys/kernel/config/gpio-sim";
    static constexpr const char* kNames[] = {"PHOTO_EYE", "ESTOP", "HEAD_READY", "PRINT_ENABLE",
                                             "BEACON"};

    GpioSimChip() : dir_(std::filesystem::path(kRoot) / ("tilejet-" + std::to_string(getpid()))) {
        std::filesystem::create_directory(dir_);
        std::filesystem::create_directory(dir_ / "bank0");
        write_file(dir_ / "bank0" / "num_lines", "5");
        for (int i = 0; i < 5; ++i) {
            const auto line = dir_ / "bank0" / ("line" + std::to_string(i));
            std::filesystem::create_directory(line);
            write_file(line / "name", kNames[i]);
        }
        write_file(dir_ / "live", "1");
        chip_ = read_file(dir_ / "bank0" / "chip_name");
        sysfs_ =
            std::filesystem::path("/sys/devices/platform") / read_file(dir_ / "dev_name") / chip_;
    }
    ~GpioSimChip() {
        std::error_code ignored;
        write_file(dir_ / "live", "0");
        for (int i = 0; i < 5; ++i)
            std::filesystem::remove(dir_ / "bank0" / ("line" + std::to_string(i)), ignored);
        std::filesystem::remove(dir_ / "bank0", ignored);
        std::filesystem::remove(dir_, ignored);
    }
    const std::string& chip() const { return chip_; }
    void drive(int offset, bool level) const {
        write_file(sysfs_ / ("sim_gpio" + std::to_string(offset)) / "pull",
                   level ? "pull-up" : "pull-down");
    }
    bool output(int offset) const {
        return read_file(sysfs_ / ("sim_gpio" + std::to_string(offset)) / "value") == "1";
    }

  private:
    std::filesystem::path dir_, sysfs_;
    std::string chip_;
};

}  // namespace

TEST_CASE("on a gpio-sim chip", "[drivers][gpiod]") {
    // gpio-sim chips are made through configfs (CONFIG_GPIO_SIM, root, a mounted
    // /sys/kernel/config). Without it there is no chip to test on: say so.
    if (!std::filesystem::exists(GpioSimChip::kRoot)) {
        WARN("SKIPPED: no gpio-sim (" << GpioSimChip::kRoot
                                      << " missing); the libgpiod backend was not run against "
                                         "a chip");
        return;
    }
    GpioSimChip sim;
    drivers::GpioConfig config;
    config.backend = "gpiod";
    config.chip = sim.chip();
    GpiodLines lines(config);

    // An input edge arrives with a kernel timestamp, on the right line, at the new level.
    timespec now{};
    clock_gettime(CLOCK_MONOTONIC, &now);
    const auto before = std::chrono::seconds(now.tv_sec) + std::chrono::nanoseconds(now.tv_nsec);
    sim.drive(0, true);
    const auto edge = lines.wait_edge(std::chrono::seconds(1));
    REQUIRE(edge);
    CHECK(edge->input == drivers::GpioInput::photo_eye);
    CHECK(edge->level);
    CHECK(edge->timestamp >= before);
    CHECK(lines.read(drivers::GpioInput::photo_eye));
    sim.drive(1, true);
    const auto estop = lines.wait_edge(std::chrono::seconds(1));
    REQUIRE(estop);
    CHECK(estop->input == drivers::GpioInput::estop);
    CHECK_FALSE(lines.wait_edge(std::chrono::milliseconds(50)));

    // Outputs reach the chip.
    lines.write(drivers::GpioOutput::print_enable, true);
    CHECK(sim.output(3));
    lines.write(drivers::GpioOutput::print_enable, false);
    CHECK_FALSE(sim.output(3));
    lines.write(drivers::GpioOutput::beacon, true);
    CHECK(sim.output(4));
}
