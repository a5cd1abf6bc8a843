#include "tilejet/colour/profile_builder.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <vector>

#include "tilejet/colour/cmyk_transform.hpp"
#include "tilejet/colour/measurements.hpp"

extern char** environ;

namespace tilejet::colour {

namespace {

// A scratch directory for colprof, which writes next to its input; removed on every path out.
class ScratchDir {
  public:
    ScratchDir() {
        std::random_device rd;
        path_ = std::filesystem::temp_directory_path() /
                ("tilejet-profile-" + std::to_string(rd()) + std::to_string(rd()));
        std::filesystem::create_directories(path_);
    }
    ~ScratchDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    const std::filesystem::path& path() const { return path_; }

  private:
    std::filesystem::path path_;
};

std::string last_lines(const std::filesystem::path& log, size_t count) {
    std::ifstream in(log);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);)
        if (!line.empty()) lines.push_back(line);
    std::string out;
    for (size_t i = lines.size() > count ? lines.size() - count : 0; i < lines.size(); ++i)
        out += (out.empty() ? "" : " | ") + lines[i];
    return out;
}

}  // namespace

void build_profile(const std::filesystem::path& measurements, const std::filesystem::path& output,
                   const ProfileBuildOptions& options) {
    // Read it ourselves first: a clear message beats colprof's when a field is missing.
    read_measurements(measurements);
    if (!(options.ink_limit_percent > 0 && options.ink_limit_percent <= 400))
        throw ColourError("--ink-limit " + std::to_string(options.ink_limit_percent) +
                          " must be in 1..400 %");

    ScratchDir scratch;
    const std::filesystem::path base = scratch.path() / "measurements";
    std::filesystem::copy_file(measurements, base.string() + ".ti3");
    const std::filesystem::path log = scratch.path() / "colprof.log";
    const std::filesystem::path target = std::filesystem::absolute(output);
    const std::string description =
        options.description.empty() ? output.stem().string() : options.description;

    std::vector<std::string> args = {"colprof",
                                     "-v",
                                     "-q" + options.quality,
                                     "-kr",  // black generation: a smooth ramp, safe on glazes
                                     "-l" + std::to_string(int(options.ink_limit_percent)),
                                     "-D" + description,
                                     "-O" + target.string(),
                                     base.string()};
    std::vector<char*> argv;
    for (std::string& a : args)
        argv.push_back(a.data());
    argv.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    pid_t pid = 0;
    const int spawned = posix_spawnp(&pid, "colprof", &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0)
        throw ColourError("cannot run ArgyllCMS colprof (" + std::string(std::strerror(spawned)) +
                          "); install Debian package 'argyll'");
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !std::filesystem::exists(target))
        throw ColourError("colprof could not build a profile from '" + measurements.string() +
                          "': " + last_lines(log, 3));
}

}  // namespace tilejet::colour
