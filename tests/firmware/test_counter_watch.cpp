// The PLC tile counter's judge (firmware/daemon/counter_watch.hpp) on readings and photo-eye
// edges the test makes up: a PLC that restarts, goes back, sticks, jumps ahead or reads a
// speed it was never asked for is a fault that counts nothing and stays until acknowledged.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "counter_watch.hpp"

using namespace tilejet;
using namespace std::chrono_literals;
using daemon::CounterWatch;
using Reading = CounterWatch::Reading;

namespace {

// 400 mm pitch, 300 mm tiles, eye at 200 mm and heads at 600 mm: one tile fits between them.
drivers::LineConfig line() {
    drivers::LineConfig l;
    l.tile_pitch_mm = 400;
    l.tile_length_mm = 300;
    l.photo_eye_mm = 200;
    l.heads_mm = 600;
    return l;
}

constexpr double kAsked = 400;  // mm/s: at half again that, a 400 mm pitch takes 2/3 s
const CounterWatch::Clock::time_point t0{};

Reading at(std::uint32_t counter, CounterWatch::Clock::duration when, double speed = kAsked,
           CounterWatch::Clock::duration took = 1ms) {
    return {counter, speed, t0 + when, took};
}

// A tile passing the eye: a pulse as long as a 300 mm tile takes at 400 mm/s.
void tile_past_eye(CounterWatch& w, std::chrono::nanoseconds when) {
    w.photo_eye(true, when, kAsked);
    w.photo_eye(false, when + 750ms, kAsked);
}

}  // namespace

TEST_CASE("the first reading sets the count, later ones count the tiles between",
          "[daemon][counter]") {
    CounterWatch w(line());
    CHECK_FALSE(w.known());
    auto v = w.judge(at(1000, 0s), kAsked);
    CHECK(w.known());
    CHECK(v.arrived == 0);  // whatever passed before the daemon looked is not its business
    CHECK_FALSE(v.fault);
    v = w.judge(at(1001, 1s), kAsked);
    CHECK(v.arrived == 1);
    CHECK(v.first_line_tile == 1000);
    CHECK(v.since == t0);  // it came after the previous read began
    v = w.judge(at(1003, 2s), kAsked);
    CHECK(v.arrived == 2);
    CHECK(v.first_line_tile == 1001);
    CHECK(v.since == t0 + 1s);
    CHECK(w.counter() == 1003);
}

TEST_CASE("a counter back to 0 (a PLC restart) is a fault that counts nothing until acknowledged",
          "[daemon][counter]") {
    CounterWatch w(line());
    w.judge(at(41237, 0s), kAsked);
    auto v = w.judge(at(0, 1s), kAsked);
    REQUIRE(v.fault);
    CHECK(v.fault->find("went back from 41237 to 0") != std::string::npos);
    CHECK(v.arrived == 0);
    CHECK(w.latched_fault() == v.fault);
    // Held: readings after it count nothing and raise nothing new.
    v = w.judge(at(1, 2s), kAsked);
    CHECK(v.arrived == 0);
    CHECK_FALSE(v.fault);
    CHECK(w.latched_fault());
    // Acknowledged: the next reading is the new base, the one after counts again.
    w.acknowledge();
    CHECK_FALSE(w.latched_fault());
    v = w.judge(at(2, 3s), kAsked);
    CHECK(v.arrived == 0);
    v = w.judge(at(3, 4s), kAsked);
    CHECK(v.arrived == 1);
    CHECK(v.first_line_tile == 2);
}

TEST_CASE("a counter back by any amount is a fault, not four billion arrivals",
          "[daemon][counter]") {
    for (std::uint32_t back : {1u, 2u, 1000u, 1u << 30, (1u << 31) - 1}) {
        CAPTURE(back);
        CounterWatch w(line());
        const std::uint32_t start = 3'000'000'000u;
        w.judge(at(start, 0s), kAsked);
        const auto v = w.judge(at(start - back, 1s), kAsked);
        REQUIRE(v.fault);
        CHECK(v.arrived == 0);
        CHECK(w.counter() == start);
    }
}

TEST_CASE("the counter wrapping past 2^32 counts the tiles that passed", "[daemon][counter]") {
    CounterWatch w(line());
    const std::uint32_t top = std::numeric_limits<std::uint32_t>::max();
    w.judge(at(top - 1, 0s), kAsked);
    const auto v = w.judge(at(1, 2s), kAsked);  // top-1 -> top -> 0 -> 1
    CHECK_FALSE(v.fault);
    CHECK(v.arrived == 3);
    CHECK(v.first_line_tile == top - 1);
}

TEST_CASE("a counter jumping ahead of what the conveyor can carry is a fault",
          "[daemon][counter]") {
    // In 2 s at half again 400 mm/s (600 mm/s), 1200 mm: three 400 mm pitches, and two for the
    // tile under the eye when the last read began: five at most.
    SECTION("five in 2 s can be") {
        CounterWatch w(line());
        w.judge(at(10, 0s), kAsked);
        const auto v = w.judge(at(15, 2s), kAsked);
        CHECK_FALSE(v.fault);
        CHECK(v.arrived == 5);
    }
    SECTION("six in 2 s cannot") {
        CounterWatch w(line());
        w.judge(at(10, 0s), kAsked);
        const auto v = w.judge(at(16, 2s), kAsked);
        REQUIRE(v.fault);
        CHECK(v.fault->find("jumped from 10 to 16") != std::string::npos);
        CHECK(v.arrived == 0);
        CHECK(w.counter() == 10);  // nothing counted
    }
    SECTION("a million at once cannot") {
        CounterWatch w(line());
        w.judge(at(10, 0s), kAsked);
        CHECK(w.judge(at(1'000'010, 1s), kAsked).fault);
    }
}

TEST_CASE("a counter stuck while the photo-eye sees tiles pass is a fault", "[daemon][counter]") {
    // One tile fits between eye and heads (plus one at each): two on the way, two more for the
    // moments between the eye's edge and the read: four tiles seen and not counted at most.
    CounterWatch w(line());
    w.judge(at(500, 0s), kAsked);
    for (int i = 0; i < 4; ++i) {
        tile_past_eye(w, std::chrono::seconds(i + 1));
        CHECK_FALSE(w.judge(at(500, std::chrono::seconds(i + 1) + 900ms), kAsked).fault);
    }
    tile_past_eye(w, 5s);
    const auto v = w.judge(at(500, 5s + 900ms), kAsked);
    REQUIRE(v.fault);
    CHECK(v.fault->find("stuck at 500") != std::string::npos);
    CHECK(v.fault->find("saw 5 tiles") != std::string::npos);
}

TEST_CASE("tiles counted take the photo-eye's lead back, glitches on the eye are not tiles",
          "[daemon][counter]") {
    CounterWatch w(line());
    w.judge(at(0, 0s), kAsked);
    for (int i = 0; i < 20; ++i) {
        tile_past_eye(w, std::chrono::seconds(i + 1));
        // A pulse of 50 ms is shorter than half a tile at half again the speed (250 ms).
        w.photo_eye(true, std::chrono::seconds(i + 1) + 800ms, kAsked);
        w.photo_eye(false, std::chrono::seconds(i + 1) + 850ms, kAsked);
        const auto v =
            w.judge(at(std::uint32_t(i + 1), std::chrono::seconds(i + 1) + 900ms), kAsked);
        CHECK_FALSE(v.fault);
        CHECK(v.arrived == 1);
    }
    CHECK(w.eye_lead() == 0);
}

TEST_CASE("a slow PLC read allows the tiles that can pass while it answers", "[daemon][counter]") {
    // A read that took 2 s at 400 mm/s: 800 mm, two pitches more than the four of a quick read.
    CounterWatch w(line());
    w.judge(at(7, 0s), kAsked);
    for (int i = 0; i < 6; ++i)
        tile_past_eye(w, std::chrono::seconds(i + 1));
    CHECK_FALSE(w.judge(at(7, 7s, kAsked, 2s), kAsked).fault);
    tile_past_eye(w, 8s);
    CHECK(w.judge(at(7, 9s, kAsked, 2s), kAsked).fault);
}

TEST_CASE("a speed reading beyond anything asked for is a fault", "[daemon][counter]") {
    // Half again 400 mm/s and 50 mm/s of overshoot: 650 mm/s.
    CounterWatch ok(line());
    CHECK_FALSE(ok.judge(at(0, 0s, 650), kAsked).fault);
    for (double speed : {651.0, 65535.0, -1.0, std::nan("")}) {
        CAPTURE(speed);
        CounterWatch w(line());
        w.judge(at(0, 0s), kAsked);
        const auto v = w.judge(at(1, 1s, speed), kAsked);
        REQUIRE(v.fault);
        CHECK(v.fault->find("speed reading") != std::string::npos);
        CHECK(v.arrived == 0);  // the counter in the same reading is not believed either
    }
}

TEST_CASE("after a lost link the next reading is a new base, whatever it says",
          "[daemon][counter]") {
    CounterWatch w(line());
    w.judge(at(100, 0s), kAsked);
    w.forget();
    // The PLC restarted while the link was down: not a fault, nothing counted (the heads are
    // resynced instead).
    auto v = w.judge(at(3, 10s), kAsked);
    CHECK_FALSE(v.fault);
    CHECK(v.arrived == 0);
    v = w.judge(at(4, 11s), kAsked);
    CHECK(v.arrived == 1);
}
