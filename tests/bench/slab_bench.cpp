// tilejet-slab-bench: `tilejet map build` on slab-scan-sized exemplars (issue 17: 4096 x 4096 px
// in 3 min and 4 GB, 8192 x 8192 px in 12 min and 8 GB, on 2 cores with default settings),
// beside the 512 px build that issue 16 holds to 60 s, in the same run. Each build runs as a
// child process, so its peak resident memory is its own (wait4's ru_maxrss). The exemplar is
// the demo design taken at 50 dpi and built for the dpi that makes it each size. Prints
// figures; never passes or fails on them.
//   tilejet-slab-bench [--sizes 512,2048,4096,8192] [--threads T] [--smoke]

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

extern char** environ;

namespace {

struct Result {
    bool ok = false;
    double seconds = 0;
    double peak_mb = 0;
    double map_mb = 0;
};

Result build(int side, int threads, const std::filesystem::path& dir) {
    // 256 px at 50 dpi: each size is the same 130 mm of stone at a higher print resolution.
    const std::string exemplar = std::string(TILEJET_SOURCE_DIR) + "/config/demo/green-marble.png";
    const std::string dpi = std::to_string(50.0 * side / 256);
    const std::string out = (dir / ("slab-" + std::to_string(side) + ".tjmap")).string();
    const std::string thread_arg = std::to_string(threads);
    std::vector<std::string> args{TILEJET_CLI, "map",     "build", exemplar, "--exemplar-dpi",
                                  "50",        "--dpi",   dpi,     "-o",     out,
                                  "--threads", thread_arg};
    std::vector<char*> argv;
    for (std::string& a : args)
        argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
    Result r;
    const auto t0 = std::chrono::steady_clock::now();
    pid_t pid = -1;
    const int spawned = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) return r;
    int status = 0;
    rusage usage{};
    if (wait4(pid, &status, 0, &usage) != pid) return r;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    r.peak_mb = double(usage.ru_maxrss) / 1024;  // kB
    std::error_code ec;
    r.map_mb = double(std::filesystem::file_size(out, ec)) / 1e6;
    std::filesystem::remove(out, ec);
    return r;
}

const char* target(int side) {
    switch (side) {
        case 512:
            return "baseline (issue 16: 60 s, 16 MB map)";
        case 4096:
            return "target 180 s, 4096 MB";
        case 8192:
            return "target 720 s, 8192 MB";
        default:
            return "";
    }
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<int> sizes{512, 2048, 4096, 8192};
    int threads = 2;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--smoke") {
            sizes = {256};  // that it runs, in CTest: the demo design as it is
        } else if (a == "--sizes" && i + 1 < argc) {
            sizes.clear();
            std::istringstream in(argv[++i]);
            for (std::string s; std::getline(in, s, ',');)
                sizes.push_back(std::stoi(s));
        } else if (a == "--threads" && i + 1 < argc) {
            threads = std::stoi(argv[++i]);
        } else {
            std::fprintf(stderr,
                         "usage: tilejet-slab-bench [--sizes 512,2048,...] [--threads T] "
                         "[--smoke]\n");
            return 2;
        }
    }
    const auto dir =
        std::filesystem::temp_directory_path() / ("tilejet-slab-bench-" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);
    std::printf("map build, default settings, %d threads: the demo design at 50 dpi, resampled\n",
                threads);
    std::printf("  %-12s %10s %12s %10s  %s\n", "exemplar", "time", "peak memory", "map",
                "compared with");
    bool all_ok = true;
    for (int side : sizes) {
        const Result r = build(side, threads, dir);
        all_ok = all_ok && r.ok;
        const std::string name = std::to_string(side) + "x" + std::to_string(side);
        if (!r.ok)
            std::printf("  %-12s FAILED after %.1f s\n", name.c_str(), r.seconds);
        else
            std::printf("  %-12s %8.1f s %9.0f MB %7.1f MB  %s\n", name.c_str(), r.seconds,
                        r.peak_mb, r.map_mb, target(side));
        std::fflush(stdout);
    }
    std::filesystem::remove_all(dir);
    return all_ok ? 0 : 1;
}
