// tilejet-soak: the simulated line at full speed for M minutes with random faults — Modbus link
// drops, reply delays, PLC fault codes, e-stops, photo-eye glitches, SIGKILL and restart of the
// daemon — while jobs keep coming. At the end every tile index of every job must be in the print
// log exactly once (more only where the daemon reported a spoiled tile), each with the SHA-256
// of an offline render. Prints what it injected, how long the line took to print again after
// each fault, and the verdict; exits 1 on any problem.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <map>
#include <random>

#include "../firmware/daemon_process.hpp"
#include "../firmware/print_log_check.hpp"

using namespace tilejet;
using namespace std::chrono_literals;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

namespace {

constexpr int kSide = 157;  // 200 x 200 mm at 20 dpi: many tiles a minute, cheap to check
constexpr int kJobTiles = 60;

struct SubmittedJob {
    std::int64_t id = 0;
    std::uint64_t seed = 0;
};

// Counts the print log's printed tiles as it grows, without re-reading it.
class PrintLogFollower {
  public:
    explicit PrintLogFollower(std::string path) : path_(std::move(path)) {}
    int printed() {
        std::ifstream in(path_);
        in.seekg(offset_);
        std::string line;
        while (std::getline(in, line)) {
            if (in.eof()) break;  // a line still being written
            offset_ += std::streamoff(line.size() + 1);
            if (line.find("\"status\":\"printed\"") != std::string::npos) ++printed_;
        }
        return printed_;
    }

  private:
    std::string path_;
    std::streamoff offset_ = 0;
    int printed_ = 0;
};

class Soak {
  public:
    Soak(std::chrono::minutes duration, std::uint64_t seed)
        : duration_(duration),
          random_(seed),
          line_(line_options()),
          daemon_(line_, dir_.path(), daemon_options()),
          log_(line_.print_log_path()) {}

    int run() {
        const auto end = Clock::now() + duration_;
        keep_jobs_queued();
        while (Clock::now() < end) {
            pause(std::uniform_int_distribution<int>(1500, 4000)(random_));
            inject_one();
            keep_jobs_queued();
        }
        std::printf("faults over; waiting for the queued jobs to finish\n");
        std::fflush(stdout);
        return finish();
    }

  private:
    static test::LinesimOptions line_options() {
        test::LinesimOptions o;
        o.speed_mm_s = 1000;  // 5 tiles/s at 200 mm pitch
        return o;
    }
    static test::DaemonOptions daemon_options() {
        test::DaemonOptions o;
        o.speed_mm_s = 1000;
        return o;
    }

    void pause(int ms) { std::this_thread::sleep_for(std::chrono::milliseconds(ms)); }
    int between(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(random_); }

    // At least two jobs not done, so the line always has work when a fault clears.
    void keep_jobs_queued() {
        try {
            int open = 0;
            for (const SubmittedJob& j : jobs_)
                if (daemon_.job(j.id).value("status", "") != "done") ++open;
            while (open < 2) {
                const std::uint64_t seed = 1000 + jobs_.size();
                const auto [status, body] = daemon_.request(
                    "POST", "/api/jobs",
                    R"({"map":")" + daemon_.add_design(TILEJET_TEST_MAP) + R"(","seed":)" +
                        std::to_string(seed) + R"(,"tiles":)" + std::to_string(kJobTiles) +
                        R"(,"tile_mm":"200x200","dpi":20})");
                if (status != 201) throw std::runtime_error("submit refused: " + body.dump());
                jobs_.push_back({body.at("id").get<std::int64_t>(), seed});
                ++open;
            }
        } catch (const std::exception& e) {
            problems_.push_back(std::string("job queue: ") + e.what());
        }
    }

    void inject_one() {
        static const char* kinds[] = {"link-drop",     "reply-delay", "plc-fault",   "e-stop",
                                      "glitch",        "daemon-kill", "plc-restart", "counter-jump",
                                      "counter-stuck", "speed-lie"};
        const std::string kind = kinds[between(0, 9)];
        ++injected_[kind];
        if (kind == "link-drop") {
            const double seconds = between(2, 20) / 10.0;
            line_.control("drop-link " + std::to_string(seconds));
            pause(int(seconds * 1000));
        } else if (kind == "reply-delay") {
            // Beyond the client's 200 ms response timeout half of the time.
            line_.control("delay " + std::to_string(between(50, 400)));
            pause(between(500, 3000));
            line_.control("delay 0");
        } else if (kind == "plc-fault") {
            line_.control("fault " + std::to_string(between(1, 999)));
            pause(between(300, 2000));
            line_.control("fault clear");
        } else if (kind == "e-stop") {
            line_.control("estop on");
            pause(between(200, 1500));
            line_.control("estop off");
            acknowledge();
        } else if (kind == "plc-restart" || kind == "counter-jump") {
            // The PLC's tile counter back to 0 (a PLC restart) or far ahead (a counter that
            // lies): the daemon stops the line until acknowledged.
            const auto counter = line_.status()["tile_counter"].get<std::uint32_t>();
            line_.control("counter " +
                          std::to_string(kind == "plc-restart"
                                             ? 0u
                                             : counter + std::uint32_t(between(50, 5000))));
            acknowledge_counter_fault();
        } else if (kind == "counter-stuck" || kind == "speed-lie") {
            // A counter that stops counting while tiles pass (the daemon sees it by the
            // photo-eye, when the line runs long enough), or a speed sensor that lies.
            line_.control(kind == "counter-stuck" ? "counter-stuck on" : "speed-reading 60000");
            pause(between(500, 4000));
            line_.control(kind == "counter-stuck" ? "counter-stuck off" : "speed-reading off");
            acknowledge_counter_fault();
        } else if (kind == "glitch") {
            line_.control("glitch " + std::to_string(between(50, 1500)));
        } else {
            daemon_.stop(SIGKILL);
            pause(between(50, 1000));
            daemon_.start();
            ++restarts_;
        }
        measure_recovery(kind);
    }

    void acknowledge() {
        // The daemon may not have seen the e-stop yet; acknowledging before it latched is
        // refused, so try until the line moves again.
        for (int i = 0; i < 50; ++i) {
            try {
                daemon_.request("POST", "/api/line/acknowledge", "");
            } catch (const std::exception&) {
            }
            if (daemon_.request("GET", "/api/status").second.value("state", "") != "e-stop") return;
            pause(100);
        }
    }

    // The daemon notices a changed counter at its next poll, unless it was not counting yet
    // (just restarted, or the link down): then there is nothing to acknowledge.
    void acknowledge_counter_fault() {
        const auto seen = [&] {
            return daemon_.request("GET", "/api/status").second.value("counter_fault", false);
        };
        for (int i = 0; i < 20 && !seen(); ++i)
            pause(100);
        for (int i = 0; i < 50 && seen(); ++i) {
            try {
                daemon_.request("POST", "/api/line/acknowledge", "");
            } catch (const std::exception&) {
            }
            pause(100);
        }
        if (seen()) problems_.push_back("a counter fault stayed after 50 acknowledges");
    }

    // From the moment the fault is gone until the next tile is printed.
    void measure_recovery(const std::string& kind) {
        const auto released = Clock::now();
        const int before = log_.printed();
        while (log_.printed() == before) {
            if (Clock::now() - released > 60s) {
                problems_.push_back("after a " + kind + " nothing printed for 60 s");
                return;
            }
            pause(10);
        }
        const double seconds = std::chrono::duration<double>(Clock::now() - released).count();
        auto& worst = max_recovery_[kind];
        worst = std::max(worst, seconds);
        max_recovery_all_ = std::max(max_recovery_all_, seconds);
    }

    int finish() {
        std::vector<json> done;
        for (const SubmittedJob& j : jobs_) {
            json job;
            test::eventually(
                [&] {
                    job = daemon_.job(j.id);
                    return job.value("status", "") == "done";
                },
                180s);
            if (job.value("status", "") != "done")
                problems_.push_back("job-" + std::to_string(j.id) + " not done: " + job.dump());
            done.push_back(job);
        }
        const auto log = line_.print_log();
        const test::ReferenceRenderer reference(TILEJET_TEST_MAP, TILEJET_TEST_CMYK_PROFILE, kSide);
        std::int64_t spoiled_total = 0;
        int tiles_checked = 0;
        for (size_t i = 0; i < jobs_.size(); ++i) {
            std::vector<std::string> hashes;
            for (int k = 0; k < kJobTiles; ++k)
                hashes.push_back(reference.hash(jobs_[i].seed, std::uint64_t(k)));
            const std::int64_t spoiled = done[i].value("spoiled", std::int64_t(0));
            spoiled_total += spoiled;
            const auto result = test::check_print_log(log, jobs_[i].id, hashes, spoiled);
            tiles_checked += result.indices_printed;
            problems_.insert(problems_.end(), result.problems.begin(), result.problems.end());
        }
        int printed = 0, missed_line = 0;
        for (const json& entry : log) {
            if (entry.value("status", "") == "printed") ++printed;
            if (entry.value("status", "") == "missed") ++missed_line;
        }
        json report{{"minutes", duration_.count()},
                    {"jobs", jobs_.size()},
                    {"tiles_printed", printed},
                    {"tile_indices_checked", tiles_checked},
                    {"spoiled_and_reprinted", spoiled_total},
                    {"line_tiles_passed_unprinted", missed_line},
                    {"faults", injected_},
                    {"daemon_restarts", restarts_},
                    {"max_recovery_s", max_recovery_},
                    {"max_recovery_all_s", max_recovery_all_},
                    {"problems", problems_}};
        std::printf("%s\n", report.dump(2).c_str());
        if (!problems_.empty()) {
            std::printf("soak FAILED: %zu problem(s); daemon log:\n%s\n", problems_.size(),
                        daemon_.log().c_str());
            return 1;
        }
        std::printf("soak passed: %d tiles, every index of %zu jobs exactly once\n", printed,
                    jobs_.size());
        return 0;
    }

    std::chrono::minutes duration_;
    std::mt19937_64 random_;
    test::TempDir dir_;
    test::LinesimProcess line_;
    test::DaemonProcess daemon_;
    PrintLogFollower log_;
    std::vector<SubmittedJob> jobs_;
    std::map<std::string, int> injected_;
    std::map<std::string, double> max_recovery_;
    double max_recovery_all_ = 0;
    int restarts_ = 0;
    std::vector<std::string> problems_;
};

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "tilejet-soak: the simulated line under random faults, then an exactly-once check"};
    int minutes = 2;
    std::uint64_t seed = std::random_device{}();
    app.add_option("--minutes", minutes, "how long to inject faults")
        ->check(CLI::Range(1, 24 * 60));
    app.add_option("--seed", seed, "fault schedule (printed, to replay a failure)");
    CLI11_PARSE(app, argc, argv);
    std::printf("tilejet-soak: %d minute(s), fault seed %llu\n", minutes,
                static_cast<unsigned long long>(seed));
    std::fflush(stdout);
    try {
        return Soak(std::chrono::minutes(minutes), seed).run();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tilejet-soak: error: %s\n", e.what());
        return 1;
    }
}
