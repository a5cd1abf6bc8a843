// The libgpiod backend without a chip: what can be checked without hardware, and a skip that
// says so when there is no gpio-sim chip to run it on.

#include <gpiod.h>

#include <catch2/catch.hpp>
#include <filesystem>

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

TEST_CASE("on a gpio-sim chip", "[drivers][gpiod]") {
    // gpio-sim chips are made through configfs (CONFIG_GPIO_SIM, root, a mounted
    // /sys/kernel/config). Without it there is no chip to test on: say so.
    if (!std::filesystem::exists("/sys/kernel/config/gpio-sim")) {
        WARN(
            "SKIPPED: no gpio-sim (/sys/kernel/config/gpio-sim missing); the libgpiod backend "
            "was not run against a chip");
        return;
    }
    WARN(
        "SKIPPED: gpio-sim exists, but the test that builds a chip through it is not written "
        "yet");
}
