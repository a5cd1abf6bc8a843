// The speed governor's rules (firmware/daemon/speed_governor.hpp) on a clock the test steps:
// slow down when rendering falls behind, stop at the slowest speed, restart on half a queue,
// speed back up step by step, and a lower [print] speed at once on reload.
#include <catch2/catch.hpp>

#include "speed_governor.hpp"

using namespace tilejet;
using namespace std::chrono_literals;
using daemon::SpeedGovernor;
using Change = SpeedGovernor::Change;

namespace {

daemon::PrintConfig print(int speed, int min_speed) {
    daemon::PrintConfig p;
    p.speed_mm_s = speed;
    p.min_speed_mm_s = min_speed;
    return p;
}

}  // namespace

TEST_CASE("rendering behind slows the conveyor to 7/10 a time, then stops it at the slowest",
          "[daemon][governor]") {
    SpeedGovernor g(print(1000, 300));
    SpeedGovernor::Clock::time_point t{};
    CHECK(g.speed() == 1000);
    CHECK(g.reason().empty());
    CHECK(g.render_behind("behind", t) == Change::slower);
    CHECK(g.speed() == 700);
    CHECK(g.reason() == "behind");
    CHECK(g.render_behind("behind", t) == Change::slower);
    CHECK(g.speed() == 490);
    CHECK(g.render_behind("behind", t) == Change::slower);
    CHECK(g.speed() == 343);
    CHECK(g.render_behind("behind", t) == Change::slower);
    CHECK(g.speed() == 300);  // never below the slowest
    CHECK_FALSE(g.stopped_for_render());
    CHECK(g.render_behind("behind", t) == Change::stop);
    CHECK(g.stopped_for_render());
    CHECK(g.render_behind("behind", t) == Change::none);  // stopped once, not again
    // The fastest asked for is still the set speed: the PLC's readings are judged by it.
    CHECK(g.fastest_asked() == 1000);
}

TEST_CASE("a conveyor stopped for rendering restarts on half the queue, or the job's rest",
          "[daemon][governor]") {
    CHECK(SpeedGovernor::ready_to_restart(8, 100) == 4);
    CHECK(SpeedGovernor::ready_to_restart(8, 2) == 2);  // the job has two tiles left
    CHECK(SpeedGovernor::ready_to_restart(1, 100) == 1);
    SpeedGovernor g(print(500, 500));
    CHECK(g.render_behind("behind", {}) == Change::stop);
    g.restarting();
    CHECK_FALSE(g.stopped_for_render());
    CHECK(g.speed() == 500);
}

TEST_CASE("a full queue brings the speed back a quarter at a time, at most every 2 s",
          "[daemon][governor]") {
    SpeedGovernor g(print(1000, 100));
    SpeedGovernor::Clock::time_point t{};
    g.render_behind("behind", t);
    g.render_behind("behind", t);
    REQUIRE(g.speed() == 490);
    CHECK_FALSE(g.render_full(t + 1s));  // too soon after the slow-down
    CHECK(g.render_full(t + 2100ms));
    CHECK(g.speed() == 612);
    CHECK_FALSE(g.render_full(t + 3s));
    CHECK(g.render_full(t + 4200ms));
    CHECK(g.speed() == 765);
    CHECK(g.render_full(t + 6300ms));
    CHECK(g.speed() == 956);
    CHECK(g.reason() == "behind");  // still below the set speed: the panel says why
    CHECK(g.render_full(t + 8400ms));
    CHECK(g.speed() == 1000);  // never above the set speed
    CHECK(g.reason().empty());
    CHECK_FALSE(g.render_full(t + 20s));
}

TEST_CASE("a lower [print] speed applies at once on reload, a higher one step by step",
          "[daemon][governor]") {
    SpeedGovernor g(print(1000, 100));
    CHECK(g.reload(print(600, 100)));
    CHECK(g.speed() == 600);
    CHECK(g.fastest_asked() == 600);
    CHECK_FALSE(g.reload(print(900, 100)));
    CHECK(g.speed() == 600);
    CHECK(g.fastest_asked() == 900);  // what the line may be asked for next
    CHECK(g.render_full(SpeedGovernor::Clock::time_point{} + 3s));
    CHECK(g.speed() == 750);
}
