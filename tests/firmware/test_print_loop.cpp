// The print loop's exactly-once rules and its answers to a PLC that restarts or lies, on the
// in-process VirtualLine with a stepped clock (virtual_rig.hpp): each test checks the job store
// and the heads' print log tile by tile. The same rules over the real wire: test_daemon_line.cpp
// and the soak.
#include <catch2/catch.hpp>

#include "virtual_rig.hpp"

using namespace tilejet;
using namespace std::chrono_literals;
using daemon::LineStatus;

namespace {

std::int64_t printed(test::VirtualRig& rig, std::int64_t id) {
    return rig.job(id).printed;
}

// The line is safe: conveyor stopped, print-enable low.
void check_parked(test::VirtualRig& rig) {
    CHECK_FALSE(rig.line().conveyor_running());
    CHECK(rig.line().belt_speed() == 0);
    CHECK_FALSE(rig.line().print_enable());
}

}  // namespace

TEST_CASE("on the virtual line a job prints every tile exactly once", "[loop]") {
    test::VirtualRig rig;
    const auto id = rig.add_job(40);
    rig.finish_exactly_once(id, 40);
    CHECK(rig.job(id).printed == 40);
    // Nothing else reached the heads printed: no tile of another job, no blank.
    for (const auto& a : rig.line().arrivals())
        if (a.printed) CHECK(a.job == "job-" + std::to_string(id));
    // With no job left the line parks.
    REQUIRE(rig.step_until([&] { return !rig.line().conveyor_running(); }, 5s));
    check_parked(rig);
}

TEST_CASE("an e-stop spoils the tile under the heads, which is printed again", "[loop]") {
    test::VirtualRig rig;
    const auto id = rig.add_job(30);
    REQUIRE(rig.step_until([&] { return printed(rig, id) >= 10; }));
    // Press it while a tile is under the heads: just after the 11th arrives.
    const std::size_t before = rig.line().arrivals().size();
    REQUIRE(rig.step_until([&] { return rig.line().arrivals().size() > before; }));
    rig.line().advance(20ms);
    rig.line().set_estop(true);
    REQUIRE(rig.step_until([&] { return rig.snapshot().status == LineStatus::estop; }, 1s));
    check_parked(rig);
    CHECK(rig.job(id).spoiled == 1);

    rig.line().set_estop(false);
    rig.run_for(200ms);
    CHECK(rig.snapshot().status == LineStatus::estop);  // latched until acknowledged
    CHECK_FALSE(rig.line().conveyor_running());
    rig.controller().post(daemon::Command::acknowledge);
    rig.finish_exactly_once(id, 30);
}

TEST_CASE("a daemon killed mid-job resumes on the same line and prints each tile once", "[loop]") {
    test::VirtualRig rig;
    const auto id = rig.add_job(40);
    for (std::int64_t at : {6, 17, 29}) {
        REQUIRE(rig.step_until([&] { return printed(rig, id) >= at; }));
        // Killed between two polls: tiles may be in flight, sent but not marked, printed but
        // not counted.
        rig.crash();
        rig.line().advance(700ms);  // the conveyor runs on; print-enable is low
        rig.boot();
    }
    rig.finish_exactly_once(id, 40);
}

TEST_CASE("SIGTERM finishes the tiles in the heads, parks the line, and the job resumes",
          "[loop]") {
    test::VirtualRig rig;
    const auto id = rig.add_job(40);
    REQUIRE(rig.step_until([&] { return printed(rig, id) >= 12; }));
    rig.controller().terminate = true;
    const auto asked = rig.line().now();
    while (rig.loop().step()) {
        REQUIRE(rig.line().now() - asked <= rig.config().print.drain_timeout + 1s);
    }
    rig.loop().finish();
    check_parked(rig);
    rig.check_store_printed_is_true(id, 40);
    CHECK(rig.line().heads_buffered() == 0);  // drained: every tile sent was printed

    rig.boot();
    rig.finish_exactly_once(id, 40);
}

TEST_CASE("tiles the heads lose in a restart are printed again, none twice", "[loop]") {
    test::VirtualRig rig;
    const auto id = rig.add_job(30);
    REQUIRE(rig.step_until([&] { return printed(rig, id) >= 8; }));
    rig.controller().post(daemon::Command::pause);
    REQUIRE(rig.step_until([&] { return rig.snapshot().status == LineStatus::paused; }, 2s));
    REQUIRE(rig.line().heads_buffered() > 0);
    rig.line().restart_heads();
    rig.controller().post(daemon::Command::resume);
    rig.finish_exactly_once(id, 30);
    CHECK(rig.job(id).missed >= 1);
}

TEST_CASE("a PLC that restarts, lies or drops the link stops the line in a named fault",
          "[loop][plc]") {
    struct Fault {
        const char* name;
        std::function<void(drivers::VirtualLine&)> inject, clear;
        const char* says;  // in the status reason
    };
    const std::vector<Fault> faults = {
        {"PLC restart: counter back to 0", [](auto& l) { l.restart_plc(); }, [](auto&) {},
         "counter"},
        {"counter back by one", [](auto& l) { l.shift_counter(-1); }, [](auto&) {}, "counter"},
        {"counter back by 1000", [](auto& l) { l.shift_counter(-1000); }, [](auto&) {}, "counter"},
        {"counter jumps ahead by 50", [](auto& l) { l.shift_counter(50); }, [](auto&) {},
         "counter"},
        {"counter stuck while the conveyor runs", [](auto& l) { l.stick_counter(true); },
         [](auto& l) { l.stick_counter(false); }, "counter"},
        {"speed reading out of range", [](auto& l) { l.set_speed_reading(60000); },
         [](auto& l) { l.set_speed_reading(std::nullopt); }, "speed"},
        {"link lost", [](auto& l) { l.set_link(false); }, [](auto& l) { l.set_link(true); },
         "link"},
    };
    for (const Fault& f : faults) {
        DYNAMIC_SECTION(f.name) {
            test::VirtualRig rig;
            const auto id = rig.add_job(40);
            REQUIRE(rig.step_until([&] { return printed(rig, id) >= 10; }));
            f.inject(rig.line());
            const auto injected = rig.line().now();
            REQUIRE(
                rig.step_until([&] { return rig.snapshot().status == LineStatus::faulted; }, 3s));
            const auto reason = rig.snapshot().reason;
            INFO("status reason: " << reason << "; after "
                                   << std::chrono::duration_cast<std::chrono::milliseconds>(
                                          rig.line().now() - injected)
                                          .count()
                                   << " ms");
            CHECK(reason.find(f.says) != std::string::npos);
            CHECK_FALSE(rig.line().print_enable());
            // Held: a second of line time later nothing moves and nothing prints.
            const std::size_t arrivals = rig.line().arrivals().size();
            rig.run_for(1s);
            CHECK(rig.snapshot().status == LineStatus::faulted);
            if (std::string(f.says) != "link") {
                check_parked(rig);
            }
            for (std::size_t i = arrivals; i < rig.line().arrivals().size(); ++i)
                CHECK_FALSE(rig.line().arrivals()[i].printed);
            rig.check_store_printed_is_true(id, 40);

            // Cleared and acknowledged, the job finishes, each tile once.
            f.clear(rig.line());
            rig.controller().post(daemon::Command::acknowledge);
            rig.finish_exactly_once(id, 40);
        }
    }
}

TEST_CASE("stop always stops, whatever the PLC does", "[loop][plc]") {
    test::VirtualRig rig;
    const auto id = rig.add_job(200);
    REQUIRE(rig.step_until([&] { return printed(rig, id) >= 5; }));
    rig.line().shift_counter(-3);                      // a fault latched...
    rig.controller().post(daemon::Command::stop_job);  // ...and the operator stops the job
    REQUIRE(rig.step_until([&] { return rig.job(id).status == jobs::JobStatus::cancelled; }, 10s));
    check_parked(rig);
    rig.check_store_printed_is_true(id, 200);
}

TEST_CASE("on the virtual line tiles printed while the counter stuck are not printed again",
          "[loop]") {
    for (const int stuck_tiles : {1, 2}) {
        DYNAMIC_SECTION("stuck for " << stuck_tiles << " tile(s)") {
            test::VirtualRig rig;
            const auto id = rig.add_job(30);
            REQUIRE(rig.step_until([&] { return printed(rig, id) >= 8; }));
            // Too short for the photo-eye check to tell: the counter misses a tile or two.
            rig.line().stick_counter(true);
            const std::size_t before = rig.line().arrivals().size();
            REQUIRE(rig.step_until(
                [&] { return rig.line().arrivals().size() >= before + std::size_t(stuck_tiles); },
                5s));
            rig.line().stick_counter(false);
            // A pause and a resume: the heads hold fewer tiles than the loop's mirror.
            rig.controller().post(daemon::Command::pause);
            rig.run_for(500ms);
            rig.controller().post(daemon::Command::resume);
            rig.finish_exactly_once(id, 30);
        }
    }
}

TEST_CASE("rendering slower than the line slows the conveyor, or stops and restarts it",
          "[loop][render]") {
    // The line takes a tile every 250 ms at 1000 mm/s, 2.5 s at the slowest 100 mm/s.
    for (const auto render_time : {400ms, 3000ms}) {
        DYNAMIC_SECTION("a tile renders in " << render_time.count() << " ms") {
            test::VirtualRig rig(render_time);
            const auto id = rig.add_job(24);
            double slowest = 1e9;
            bool said_slowed = false, stopped_mid_job = false;
            REQUIRE(rig.step_until(
                [&] {
                    const auto s = rig.snapshot();
                    if (rig.line().conveyor_running())
                        slowest = std::min(slowest, rig.line().belt_speed());
                    else if (printed(rig, id) > 2)
                        stopped_mid_job = true;
                    said_slowed |= s.reason.find("slowed") != std::string::npos ||
                                   s.reason.find("render") != std::string::npos;
                    return rig.job_done(id);
                },
                300s));
            rig.check_exactly_once(id, 24);
            CHECK(said_slowed);
            CHECK(slowest < 1000);
            if (render_time > 2500ms) CHECK(stopped_mid_job);
        }
    }
}
