// tilejet-eval-bench: how long `tilejet eval` takes on a wall of the demo design (issue 8 asks
// for a 200-tile wall of 512x512 tiles in under 2 minutes on 2 cores). Runs the real command
// and prints the time beside the machine's load; it never passes or fails on time.
//   tilejet-eval-bench [MAP] [--tiles N] [--tile-size WxH] [--threads T]
// MAP defaults to out/demo/green-marble.tjmap (scripts/demo makes it).

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

namespace {

std::string load_average() {
    std::ifstream in("/proc/loadavg");
    std::string one, five, fifteen;
    in >> one >> five >> fifteen;
    return one + " " + five + " " + fifteen;
}

}  // namespace

int main(int argc, char** argv) {
    std::string map = std::string(TILEJET_SOURCE_DIR) + "/out/demo/green-marble.tjmap";
    std::string tiles = "200", size = "512x512", threads = "2";
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--tiles" && i + 1 < argc)
            tiles = argv[++i];
        else if (a == "--tile-size" && i + 1 < argc)
            size = argv[++i];
        else if (a == "--threads" && i + 1 < argc)
            threads = argv[++i];
        else
            map = a;
    }
    if (!std::filesystem::exists(map)) {
        std::fprintf(stderr, "tilejet-eval-bench: no map '%s' (run scripts/demo first)\n",
                     map.c_str());
        return 2;
    }
    const auto out =
        std::filesystem::temp_directory_path() / ("tilejet-eval-bench-" + std::to_string(getpid()));
    const std::string command = std::string(TILEJET_CLI) + " eval " + map +
                                " --seed 2026 --tiles " + tiles + " --tile-size " + size +
                                " --threads " + threads + " -o " + out.string() + " > /dev/null";
    std::printf("tilejet eval: %s tiles of %s px, %s threads, %u cores on the machine\n",
                tiles.c_str(), size.c_str(), threads.c_str(), std::thread::hardware_concurrency());
    std::printf("  load average before: %s\n", load_average().c_str());
    const auto t0 = std::chrono::steady_clock::now();
    const int status = std::system(command.c_str());
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("  load average after:  %s\n", load_average().c_str());
    std::printf("  %-44s %10.1f s   (target: under 120 s on 2 cores)\n",
                "evaluation, four walls (tilejet + 3 baselines)", s);
    std::error_code ec;
    std::filesystem::remove_all(out, ec);
    return status == 0 ? 0 : 1;
}
