#pragma once

// VirtualRig: a PrintLoop on a VirtualLine, stepped by the test in the test's thread: the line's
// stepped clock is the loop's clock, tiles render in the turn that takes them, and the job store
// is a real one in a temp folder (a crash is the loop destroyed without finish(), its store on
// disk). Every run goes the same way, thousands of tiles in a second or two.
#include <catch2/catch.hpp>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <sstream>
#include <string>

#include "../../firmware/daemon/print_loop.hpp"
#include "../drivers/linesim_process.hpp"
#include "tilejet/drivers/virtual_line.hpp"
#include "tilejet/synth/map_file.hpp"

namespace tilejet::test {

class VirtualClock : public daemon::LoopClock {
  public:
    explicit VirtualClock(drivers::VirtualLine& line) : line_(line) {}
    Clock::time_point now() const override { return line_.now(); }
    void sleep_for(Clock::duration d) override { line_.advance(d); }

  private:
    drivers::VirtualLine& line_;
};

// The default config with its paths made absolute and the test's CMYK profile (the shipped
// one names the profile scripts/demo builds, absent in a clean clone), a small line and a job
// store in `dir`. Its register map is not used: there is no wire.
inline daemon::DaemonConfig virtual_config(const std::filesystem::path& dir) {
    const std::filesystem::path config_dir = std::filesystem::path(TILEJET_SOURCE_DIR) / "config";
    std::ifstream in(config_dir / "tilejet.toml");
    std::stringstream text;
    text << in.rdbuf();
    std::string toml = text.str();
    const auto replace_line = [&](const std::string& key, const std::string& value) {
        const size_t at = toml.find("\n" + key + " = ");
        REQUIRE(at != std::string::npos);
        const size_t end = toml.find('\n', at + 1);
        toml.replace(at + 1, end - at - 1, key + " = \"" + value + "\"");
    };
    replace_line("register_map", (config_dir / "registers.toml").string());
    replace_line("output_profile", TILEJET_TEST_CMYK_PROFILE);
    replace_line("database", (dir / "jobs.db").string());
    replace_line("previews", (dir / "previews").string());
    replace_line("designs", dir.string());
    replace_line("profiles", dir.string());
    std::ofstream(dir / "tilejetd.toml") << toml;
    daemon::DaemonConfig c = daemon::load_daemon_config((dir / "tilejetd.toml").string());
    c.drivers.line.tile_length_mm = 200;
    c.drivers.line.tile_pitch_mm = 250;
    c.drivers.line.photo_eye_mm = 100;
    c.drivers.line.heads_mm = 700;
    c.storage.preview_tiles = 0;
    c.render.threads = 1;
    c.render.queue_tiles = 4;
    c.render.dpi = 20;
    c.print.speed_mm_s = 1000;
    c.print.min_speed_mm_s = 100;
    c.print.head_buffer_tiles = 2;
    c.print.drain_timeout = std::chrono::seconds(5);
    return c;
}

class VirtualRig {
  public:
    // `render_time`: how long each tile takes to render, on the line's clock (0: no time).
    explicit VirtualRig(std::chrono::milliseconds render_time = std::chrono::milliseconds(0))
        : render_time_(render_time),
          config_(virtual_config(dir_.path())),
          line_(config_.drivers.line, config_.print.head_buffer_tiles),
          clock_(line_) {
        boot();
    }
    ~VirtualRig() {
        if (loop_) loop_->finish();
    }

    drivers::VirtualLine& line() { return line_; }
    daemon::Controller& controller() { return *controller_; }
    daemon::PrintLoop& loop() { return *loop_; }
    const daemon::DaemonConfig& config() const { return config_; }

    // A new daemon on the same line and store.
    void boot() {
        controller_ = std::make_unique<daemon::Controller>();
        daemon::LoopRig rig;
        rig.make_line = [this] { return line_.make_line_control(); };
        rig.gpio = line_.make_gpio();
        rig.heads = line_.make_heads();
        rig.store = std::make_unique<jobs::JobStore>(config_.storage.database);
        rig.clock = &clock_;
        rig.render_in_turn = true;
        rig.render_time = render_time_;
        loop_ = std::make_unique<daemon::PrintLoop>(config_, *controller_, std::move(rig));
        loop_->start();
    }
    // SIGKILL: the loop goes without parking the line; the GPIO side drops print-enable.
    void crash() {
        loop_.reset();
        line_.daemon_gone();
    }

    std::int64_t add_job(std::int64_t tiles) {
        jobs::JobStore store(config_.storage.database);
        jobs::JobSpec spec;
        spec.map = TILEJET_TEST_MAP;
        spec.map_id = synth::load_texture_map(TILEJET_TEST_MAP).id_hex();
        spec.seed = 4242;
        spec.tiles = tiles;
        spec.tile_width_mm = spec.tile_height_mm = 200;
        spec.dpi = 20;
        return store.add_job(spec).id;
    }
    jobs::Job job(std::int64_t id) {
        jobs::JobStore store(config_.storage.database);
        return *store.job(id);
    }
    std::optional<jobs::TileState> tile_state(std::int64_t job, std::int64_t index) {
        jobs::JobStore store(config_.storage.database);
        return store.tile_state(job, index);
    }

    // Steps until `done` holds (checked after each turn), at most `limit` of line time; false
    // when the limit passed first or the loop ended.
    bool step_until(const std::function<bool()>& done,
                    std::chrono::steady_clock::duration limit = std::chrono::seconds(120)) {
        const auto until = line_.now() + limit;
        while (line_.now() < until) {
            if (!loop_->step()) return done();
            if (done()) return true;
        }
        return false;
    }
    // Steps for `d` of line time, whatever happens.
    void run_for(std::chrono::steady_clock::duration d) {
        step_until([] { return false; }, d);
    }
    bool job_done(std::int64_t id) { return job(id).status == jobs::JobStatus::done; }
    daemon::LineSnapshot snapshot() const { return controller_->snapshot(); }

    // How often the heads printed each tile of job `id` (from the line's arrivals).
    std::map<std::int64_t, int> prints(std::int64_t id) const {
        std::map<std::int64_t, int> n;
        const std::string name = "job-" + std::to_string(id);
        for (const auto& a : line_.arrivals())
            if (a.printed && a.job == name) ++n[std::int64_t(a.tile)];
        return n;
    }

    // Every tile of the job printed once; a tile the store says was spoiled may have been
    // printed once more per spoil. Failures name the tile.
    void check_exactly_once(std::int64_t id, std::int64_t tiles) {
        const auto n = prints(id);
        jobs::JobStore store(config_.storage.database);
        for (std::int64_t k = 0; k < tiles; ++k) {
            const auto it = n.find(k);
            const int printed = it == n.end() ? 0 : it->second;
            const int spoiled = store.times_spoiled(id, k);
            INFO("tile " << k << " printed " << printed << " times, spoiled " << spoiled);
            CHECK(printed == 1 + spoiled);
        }
        CHECK(int(n.size()) == tiles);
    }

    // Steps until job `id` is done (at most two minutes of line time), then checks each of its
    // `tiles` was printed once.
    void finish_exactly_once(std::int64_t id, std::int64_t tiles) {
        REQUIRE(step_until([&] { return job_done(id); }));
        check_exactly_once(id, tiles);
    }

    // No tile is marked printed that the heads did not print.
    void check_store_printed_is_true(std::int64_t id, std::int64_t tiles) {
        const auto n = prints(id);
        for (std::int64_t k = 0; k < tiles; ++k) {
            if (tile_state(id, k) != jobs::TileState::printed) continue;
            INFO("tile " << k << " is marked printed");
            CHECK(n.count(k) == 1);
        }
    }

  private:
    std::chrono::milliseconds render_time_;
    TempDir dir_;
    daemon::DaemonConfig config_;
    drivers::VirtualLine line_;
    VirtualClock clock_;
    std::unique_ptr<daemon::Controller> controller_;
    std::unique_ptr<daemon::PrintLoop> loop_;
};

}  // namespace tilejet::test
