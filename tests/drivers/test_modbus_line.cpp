// tilejet's Modbus client against tilejet-linesim, a separate process speaking real Modbus TCP.

#include <catch2/catch.hpp>
#include <thread>

#include "linesim_process.hpp"
#include "tilejet/drivers/modbus/modbus_line_control.hpp"

using namespace tilejet;
using namespace std::chrono_literals;
using Catch::Matchers::Contains;

namespace {

drivers::ModbusLineControl client(const test::LinesimProcess& sim) {
    return drivers::ModbusLineControl(sim.config().modbus, sim.config().registers);
}

// Reads until the link answers again, as the daemon's poll loop would.
bool read_until_up(drivers::ModbusLineControl& line, std::chrono::milliseconds timeout) {
    return test::eventually(
        [&] {
            try {
                line.read_state();
                return true;
            } catch (const drivers::LinkError&) {
                return false;
            }
        },
        timeout);
}

}  // namespace

TEST_CASE("every register in the map reads, every holding register writes", "[drivers][modbus]") {
    test::LinesimProcess sim;
    auto line = client(sim);
    // Power-up state as [sim] says: stopped, setpoint 1000, ready.
    CHECK(line.read("ready") == 1);
    CHECK(line.read("running") == 0);
    CHECK(line.read("fault_code") == 0);
    CHECK(line.read("speed_actual") == 0);
    CHECK(line.read("tile_counter") == 0);
    CHECK(line.read("estop") == 0);
    CHECK(line.read("speed_setpoint") == 1000);
    CHECK(line.read("run_command") == 0);

    line.write("speed_setpoint", 1234);
    CHECK(line.read("speed_setpoint") == 1234);
    CHECK(sim.status()["speed_setpoint"] == 1234);  // seen from the simulator's side too
    line.write("run_command", 1);
    CHECK(line.read("run_command") == 1);
    CHECK(line.read("running") == 1);
    CHECK(line.read("speed_actual") == 1234);
    line.write("run_command", 0);
    CHECK(line.read("run_command") == 0);
    CHECK(line.read("running") == 0);

    // Every register of the map, read in one pass, matches the one-by-one reads.
    const auto all = line.read_all();
    CHECK(all.size() == sim.config().registers.registers().size());
    for (const auto& r : sim.config().registers.registers())
        CHECK(all.at(r.name) == line.read(r.name));
}

TEST_CASE("the tile counter (u32 across two registers) counts tiles at the heads",
          "[drivers][modbus]") {
    test::LinesimOptions o;
    o.speed_mm_s = 2000;  // 200 mm pitch: 10 tiles/s; first tile at the heads after 125 ms
    test::LinesimProcess sim(o);
    auto line = client(sim);
    line.run();
    std::this_thread::sleep_for(600ms);
    line.stop();
    const auto state = line.read_state();
    // 0.6 s at 2000 mm/s = 1200 mm of belt: tiles 0..4 have reached heads_mm = 250.
    CHECK(state.tile_counter >= 4);
    CHECK(state.tile_counter <= 6);
    CHECK(state.tile_counter == sim.status()["tile_counter"].get<std::uint32_t>());
    CHECK(sim.print_log().size() == state.tile_counter);
}

TEST_CASE("writes are checked against the map before they are sent", "[drivers][modbus]") {
    test::LinesimProcess sim;
    auto line = client(sim);
    REQUIRE_THROWS_AS(line.write("speed_setpoint", 2001), drivers::RegisterError);
    REQUIRE_THROWS_WITH(line.write("speed_setpoint", 2001),
                        Contains("holding register 100 'speed_setpoint'") && Contains("max 2000"));
    REQUIRE_THROWS_WITH(line.write("tile_counter", 1), Contains("'tile_counter' is read-only"));
    REQUIRE_THROWS_WITH(line.read("no_such"), Contains("no register named 'no_such'"));
    CHECK(line.read("speed_setpoint") == 1000);  // nothing was written
}

TEST_CASE("fault CODE stops the line, fault clear makes it ready again",
          "[drivers][modbus][fault]") {
    test::LinesimOptions o;
    o.start_running = true;
    test::LinesimProcess sim(o);
    auto line = client(sim);
    REQUIRE(line.read_state().running);
    sim.control("fault 42");
    auto s = line.read_state();
    CHECK(s.fault_code == 42);
    CHECK_FALSE(s.ready);
    CHECK_FALSE(s.running);
    CHECK_FALSE(s.run_commanded);
    line.run();  // refused while faulted
    CHECK_FALSE(line.read_state().running);
    sim.control("fault clear");
    s = line.read_state();
    CHECK(s.fault_code == 0);
    CHECK(s.ready);
    CHECK_FALSE(s.running);  // a cleared fault does not restart the line by itself
    line.run();
    CHECK(line.read_state().running);
}

TEST_CASE("e-stop as the PLC reports it", "[drivers][modbus][fault]") {
    test::LinesimOptions o;
    o.start_running = true;
    test::LinesimProcess sim(o);
    auto line = client(sim);
    sim.control("estop on");
    auto s = line.read_state();
    CHECK(s.estop);
    CHECK_FALSE(s.ready);
    CHECK_FALSE(s.running);
    sim.control("estop off");
    s = line.read_state();
    CHECK_FALSE(s.estop);
    CHECK(s.ready);
}

TEST_CASE("stop-conveyor and start-conveyor from the line side", "[drivers][modbus][fault]") {
    test::LinesimOptions o;
    o.start_running = true;
    test::LinesimProcess sim(o);
    auto line = client(sim);
    sim.control("stop-conveyor");
    auto s = line.read_state();
    CHECK_FALSE(s.running);
    CHECK(s.speed_mm_s == 0);
    CHECK_FALSE(s.run_commanded);
    sim.control("start-conveyor");
    s = line.read_state();
    CHECK(s.running);
    CHECK(s.speed_mm_s == 1000);
}

TEST_CASE("slow replies: within the timeout they arrive, beyond it a clear timeout, then recovery",
          "[drivers][modbus][fault]") {
    test::LinesimProcess sim;  // response timeout 200 ms
    auto line = client(sim);
    sim.control("delay 80");
    auto t0 = std::chrono::steady_clock::now();
    CHECK(line.read("speed_setpoint") == 1000);
    CHECK(std::chrono::steady_clock::now() - t0 >= 80ms);

    sim.control("delay 500");
    t0 = std::chrono::steady_clock::now();
    REQUIRE_THROWS_WITH(line.read("fault_code"),
                        Contains("reading input register 2 'fault_code'") && Contains("timed out"));
    const auto waited = std::chrono::steady_clock::now() - t0;
    CHECK(waited >= 190ms);
    CHECK(waited < 450ms);  // bounded by the timeout, not by the simulator
    // The next call reconnects, and the connect-time sync read (the whole input block, which
    // names every register in it) times out the same way.
    REQUIRE_THROWS_WITH(line.read("fault_code"), Contains("fault_code") && Contains("timed out"));

    sim.control("delay 0");
    CHECK(read_until_up(line, 2s));
    CHECK(line.read("speed_setpoint") == 1000);
}

TEST_CASE("a link dropped mid-transfer reconnects and re-syncs within 2 s",
          "[drivers][modbus][fault]") {
    test::LinesimProcess sim;
    auto line = client(sim);
    line.set_speed(777);
    const auto syncs_before = line.resyncs();

    // A request in flight (the reply is held back 300 ms) when the link is cut.
    sim.control("delay 150");
    std::thread cut([&] {
        std::this_thread::sleep_for(50ms);
        // While the link is down the PLC "restarts": its setpoint is back to a default.
        sim.control("drop-link 0.5");
        sim.control("set speed_setpoint 100");
        sim.control("delay 0");
    });
    const auto t0 = std::chrono::steady_clock::now();
    REQUIRE_THROWS_AS(line.read_state(), drivers::LinkError);
    cut.join();
    CHECK_FALSE(line.connected());
    // Writes during the outage fail at once; nothing is queued.
    CHECK_THROWS_AS(line.run(), drivers::LinkError);

    REQUIRE(read_until_up(line, 2s));
    const auto recovered = std::chrono::steady_clock::now() - t0;
    CHECK(recovered < 2s);
    CHECK(line.resyncs() > syncs_before);
    // Re-synced: the retained setpoint is back at what tilejet asked for ...
    CHECK(line.read("speed_setpoint") == 777);
    CHECK(sim.status()["speed_setpoint"] == 777);
    // ... and the run command made during the outage was not replayed.
    CHECK(line.read("run_command") == 0);
    CHECK(sim.status()["running"] == false);
}

TEST_CASE("a simulator that is gone gives a clear error at once, with back-off",
          "[drivers][modbus][fault]") {
    drivers::ModbusConfig config;
    {
        test::LinesimProcess sim;
        config = sim.config().modbus;
    }  // killed: nothing listens on that port now
    const auto map = drivers::load_register_map(TILEJET_SOURCE_DIR "/config/registers.toml");
    drivers::ModbusLineControl line(config, map);
    const auto t0 = std::chrono::steady_clock::now();
    REQUIRE_THROWS_WITH(line.read_state(), Contains("cannot connect"));
    REQUIRE_THROWS_WITH(line.read_state(), Contains("next reconnect attempt in"));
    CHECK(std::chrono::steady_clock::now() - t0 < 500ms);
}

TEST_CASE("a context belongs to the thread that made it", "[drivers][modbus]") {
    test::LinesimProcess sim;
    auto line = client(sim);
    std::string error;
    std::thread other([&] {
        try {
            line.read_state();
        } catch (const std::logic_error& e) {
            error = e.what();
        }
    });
    other.join();
    CHECK_THAT(error, Contains("one per thread"));
}

TEST_CASE("RTU: a missing serial device is a clear link error (no RTU device to test with)",
          "[drivers][modbus]") {
    drivers::ModbusConfig config;
    config.transport = "rtu";
    config.device = "/dev/tilejet-no-such-tty";
    const auto map = drivers::load_register_map(TILEJET_SOURCE_DIR "/config/registers.toml");
    drivers::ModbusLineControl line(config, map);
    CHECK(line.endpoint() == "rtu /dev/tilejet-no-such-tty");
    REQUIRE_THROWS_AS(line.read_state(), drivers::LinkError);
    REQUIRE_THROWS_WITH(line.read("ready"), Contains("rtu /dev/tilejet-no-such-tty"));
}
