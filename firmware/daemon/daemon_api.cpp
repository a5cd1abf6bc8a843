#include "daemon_api.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "job_setup.hpp"
#include "line_faults.hpp"
#include "tilejet/api/job_request.hpp"
#include "tilejet/colour/cmyk_transform.hpp"
#include "tilejet/synth/map_file.hpp"

namespace tilejet::daemon {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// The rate shown is over this last stretch: long enough to smooth one tile's jitter, short
// enough that a stop shows within a minute.
constexpr auto kRateWindow = std::chrono::seconds(60);
constexpr int kNextTiles = 6;

json files_in(const std::string& folder, std::initializer_list<const char*> extensions) {
    json list = json::array();
    std::error_code ec;
    if (folder.empty() || !fs::is_directory(folder, ec)) return list;
    std::vector<fs::path> found;
    for (const auto& entry : fs::directory_iterator(folder, ec)) {
        const std::string ext = entry.path().extension().string();
        for (const char* e : extensions)
            if (ext == e && entry.is_regular_file(ec)) found.push_back(entry.path());
    }
    std::sort(found.begin(), found.end());
    for (const fs::path& p : found)
        list.push_back({{"name", p.filename().string()},
                        {"path", fs::absolute(p).lexically_normal().string()},
                        {"bytes", fs::file_size(p, ec)}});
    return list;
}

// Written beside its final name and renamed: a reader never sees half a file. An existing file
// is never replaced: queued jobs name it, and their tiles must stay what they were.
// The file a job names in one of the daemon's folders (the API let through a plain name only):
// a regular file itself, never a FIFO, a device or a symlink to elsewhere.
fs::path named_file(const std::string& folder, const std::string& name, const std::string& field,
                    const std::string& kind) {
    if (folder.empty())
        throw api::ApiError(
            400, field,
            field + ": no " + kind + "s folder is configured ([storage] " + kind + "s)");
    const fs::path p = fs::path(folder) / name;
    struct stat st {};
    if (lstat(p.c_str(), &st) != 0 || !S_ISREG(st.st_mode))
        throw api::ApiError(400, field,
                            field + ": no " + kind + " '" + name + "' in the " + kind +
                                "s folder (GET /api/" + kind + "s lists them)");
    return p;
}

fs::path upload(const std::string& folder, const std::string& name, const std::string& bytes,
                const char* extension, const char* kind,
                const std::function<void(const fs::path&)>& check) {
    if (folder.empty())
        throw api::ApiError(501, "name",
                            std::string("no folder for ") + kind + "s in the config ([storage])");
    if (fs::path(name).extension() != extension)
        throw api::ApiError(400, "name",
                            "name: a " + std::string(kind) + " file ends in " + extension);
    if (bytes.empty()) throw api::ApiError(400, "body", "body: empty file");
    const fs::path target = fs::path(folder) / name;
    const auto exists = [&] {
        return api::ApiError(409, "name",
                             "name: '" + name + "' exists; upload it under a new name");
    };
    if (fs::exists(target)) throw exists();
    fs::create_directories(folder);
    // A temp file of this upload's own: created exclusively (O_EXCL never follows a symlink
    // planted at the name), then published without ever replacing a file, so of two uploads
    // of one name exactly one wins and the file holds its bytes.
    std::string pattern = (fs::path(folder) / ("." + name + ".XXXXXX")).string();
    const int fd = ::mkostemp(pattern.data(), O_CLOEXEC);
    if (fd < 0)
        throw std::runtime_error("cannot create a file in " + folder + ": " + std::strerror(errno));
    const fs::path temp = pattern;
    struct Temp {
        int fd;
        fs::path path;
        ~Temp() {  // published or not, the temp name goes
            if (fd >= 0) ::close(fd);
            std::error_code ignored;
            fs::remove(path, ignored);
        }
    } guard{fd, temp};
    for (size_t done = 0; done < bytes.size();) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0)
            throw std::runtime_error("cannot write " + temp.string() + ": " + std::strerror(errno));
        done += size_t(n);
    }
    if (::fchmod(fd, 0644) != 0 || ::fsync(fd) != 0)
        throw std::runtime_error("cannot write " + temp.string() + ": " + std::strerror(errno));
    ::close(std::exchange(guard.fd, -1));
    try {
        check(temp);
    } catch (const std::exception& e) {
        throw api::ApiError(400, "body",
                            std::string("body: not a usable ") + kind + ": " + e.what());
    }
    if (::renameat2(AT_FDCWD, temp.c_str(), AT_FDCWD, target.c_str(), RENAME_NOREPLACE) != 0) {
        if (errno == EEXIST) throw exists();
        if (errno != EINVAL && errno != ENOSYS)
            throw std::runtime_error("cannot publish " + target.string() + ": " +
                                     std::strerror(errno));
        // A file system without RENAME_NOREPLACE: a hard link fails the same way on a file
        // that exists.
        if (::link(temp.c_str(), target.c_str()) != 0) {
            if (errno == EEXIST) throw exists();
            throw std::runtime_error("cannot publish " + target.string() + ": " +
                                     std::strerror(errno));
        }
    }
    return target;
}

}  // namespace

DaemonApi::DaemonApi(const DaemonConfig& config, Controller& controller)
    : config_(config),
      controller_(controller),
      store_(config.storage.database),
      previews_(config.colour) {
    if (config.api.access.users.empty())
        log_line("no [[users]] in the config: nobody can sign in to the API or the panel");
}

double DaemonApi::rate_tiles_per_min(std::int64_t printed) {
    const auto now = std::chrono::steady_clock::now();
    rate_samples_.emplace_back(now, printed);
    while (now - rate_samples_.front().first > kRateWindow)
        rate_samples_.pop_front();
    const auto& [t0, n0] = rate_samples_.front();
    const double seconds = std::chrono::duration<double>(now - t0).count();
    return seconds < 2 ? 0.0 : double(printed - n0) * 60.0 / seconds;
}

std::optional<jobs::Job> DaemonApi::wall_job(const LineSnapshot& s) {
    if (s.job) return store_.job(*s.job);
    for (const jobs::Job& j : store_.jobs(20))
        if (j.printed > 0) return j;
    return std::nullopt;
}

json DaemonApi::status() {
    const LineSnapshot s = controller_.snapshot();
    json j{{"state", std::string(to_string(s.status))},
           {"reason", s.reason},
           {"link_up", s.link_up},
           {"estop_latched", s.estop_latched},
           {"conveyor_running", s.conveyor_running},
           {"speed_setpoint_mm_s", s.speed_setpoint_mm_s},
           {"speed_mm_s", s.speed_mm_s},
           {"plc_fault_code", s.plc_fault_code},
           {"counter_fault", s.counter_fault},
           {"tile_counter", s.tile_counter},
           {"heads_queue", s.heads_queue},
           {"rendered_ahead", s.rendered_ahead},
           {"line_tiles_printed", s.line_tiles_printed},
           {"line_tiles_missed", s.line_tiles_missed},
           {"blanks", s.blanks},
           {"spoiled", s.spoiled},
           {"previews", config_.storage.previews},
           {"faults", line_faults(s)},
           {"next_tiles", json::array()},
           {"wall", nullptr}};
    std::lock_guard lock(mutex_);
    j["rate_tiles_per_min"] = rate_tiles_per_min(s.line_tiles_printed);
    if (s.job) {
        if (auto job = store_.job(*s.job)) {
            j["job"] = api::job_json(*job);
            j["job"]["remaining"] = std::max<std::int64_t>(0, job->spec.tiles - job->printed);
            // Next to print: what the heads hold, in order, then what goes to them next.
            json next = json::array();
            for (const jobs::QueuedTile& t : store_.heads_queue())
                if (t.job == job->id && int(next.size()) < kNextTiles) next.push_back(t.index);
            for (std::int64_t k : store_.upcoming(*job, kNextTiles))
                if (int(next.size()) < kNextTiles) next.push_back(k);
            j["next_tiles"] = next;
        }
    }
    // What the wall preview shows: the panel fetches it again when `printed` moves.
    if (const auto w = wall_job(s))
        j["wall"] = {{"job", w->id}, {"printed", w->printed}, {"name", w->name()}};
    return j;
}

json DaemonApi::submit(const jobs::JobSpec& submitted) {
    // Rejected here rather than when the line reaches the job: a queue must not stall on a
    // job that can never print.
    jobs::JobSpec spec = submitted;
    spec.map = named_file(config_.storage.designs, spec.map, "map", "design").string();
    if (!spec.profile.empty())
        spec.profile =
            named_file(config_.storage.profiles, spec.profile, "profile", "profile").string();
    double map_dpi = 0;
    try {
        const synth::TextureMap map = synth::load_texture_map(spec.map);
        spec.map_id = map.id_hex();
        map_dpi = map.build.dpi;
    } catch (const std::exception& e) {
        throw api::ApiError(400, "map", std::string("map: ") + e.what());
    }
    // A design prints at its physical size: at the dpi its map is built for, never rescaled.
    // Maps that record no dpi (built before they did) print at any.
    if (spec.dpi == 0) spec.dpi = map_dpi > 0 ? int(std::lround(map_dpi)) : config_.render.dpi;
    if (map_dpi > 0 && std::abs(spec.dpi - map_dpi) > 0.5) {
        char built[32];
        std::snprintf(built, sizeof built, "%g", map_dpi);
        throw api::ApiError(400, "dpi",
                            "dpi: the job asks for " + std::to_string(spec.dpi) + " dpi, but " +
                                spec.map + " is built for " + built + " dpi: submit at " + built +
                                " dpi, or build the map again with --dpi " +
                                std::to_string(spec.dpi));
    }
    api::check_tile_fits(spec);
    try {
        colour::CmykTransform transform(job_colour(spec, config_.colour));
    } catch (const std::exception& e) {
        throw api::ApiError(400, "profile", std::string("profile: ") + e.what());
    }
    std::lock_guard lock(mutex_);
    return api::job_json(store_.add_job(spec));
}

json DaemonApi::jobs() {
    std::lock_guard lock(mutex_);
    json list = json::array();
    for (const jobs::Job& j : store_.jobs())
        list.push_back(api::job_json(j));
    return list;
}

std::optional<json> DaemonApi::job(std::int64_t id) {
    std::lock_guard lock(mutex_);
    auto j = store_.job(id);
    if (!j) return std::nullopt;
    return api::job_json(*j);
}

json DaemonApi::command(std::string_view name) {
    if (name == "pause")
        controller_.post(Command::pause);
    else if (name == "resume")
        controller_.post(Command::resume);
    else if (name == "stop")
        controller_.post(Command::stop_job);
    else if (name == "acknowledge")
        controller_.post(Command::acknowledge);
    else
        throw api::ApiError(404, "command", "no command '" + std::string(name) + "'");
    return {{"accepted", std::string(name)}};
}

namespace {

// The job's design or profile on disk cannot give its tiles (replaced, damaged): the job and
// the files disagree, which the panel shows rather than a picture of other tiles.
api::ApiError job_files_disagree(const JobSetupError& e) {
    return api::ApiError(409, "map", e.what());
}

}  // namespace

std::string DaemonApi::tile_png(std::int64_t id, std::int64_t index, int max_side) {
    std::optional<jobs::Job> job;
    {
        std::lock_guard lock(mutex_);
        job = store_.job(id);
    }
    if (!job) throw api::ApiError(404, "id", "no job " + std::to_string(id));
    if (index < 0 || index >= job->spec.tiles)
        throw api::ApiError(
            404, "tile",
            "tile: " + job->name() + " has tiles 0.." + std::to_string(job->spec.tiles - 1));
    try {
        return previews_.tile_png(*job, index, max_side);
    } catch (const JobSetupError& e) {
        throw job_files_disagree(e);
    }
}

std::string DaemonApi::wall_png(int tiles, int max_side) {
    std::optional<jobs::Job> job;
    std::vector<std::int64_t> indices;
    {
        std::lock_guard lock(mutex_);
        job = wall_job(controller_.snapshot());
        if (job) indices = store_.printed_tiles(job->id, tiles);
    }
    if (!job || indices.empty()) throw api::ApiError(404, "", "no tiles printed yet");
    try {
        return previews_.wall_png(*job, indices, max_side);
    } catch (const JobSetupError& e) {
        throw job_files_disagree(e);
    }
}

json DaemonApi::designs() {
    json list = files_in(config_.storage.designs, {".tjmap"});
    for (json& d : list)
        if (const auto dpi = design_dpi(d["path"].get<std::string>())) d["dpi"] = *dpi;
    return list;
}

std::optional<double> DaemonApi::design_dpi(const std::string& path) {
    // Loading a map takes a while: each file's dpi is read once per version of the file.
    std::error_code ec;
    const auto size = fs::file_size(path, ec);
    const auto mtime = fs::last_write_time(path, ec);
    if (ec) return std::nullopt;
    std::lock_guard lock(design_dpi_mutex_);
    auto& known = design_dpi_[path];
    if (!known.read || known.size != size || known.mtime != mtime) {
        try {
            const double dpi = synth::load_texture_map(path).build.dpi;
            known = {size, mtime, dpi > 0 ? std::optional<double>(dpi) : std::nullopt, true};
        } catch (const std::exception&) {
            return std::nullopt;  // not a map this daemon can print; submit says why
        }
    }
    return known.dpi;
}

json DaemonApi::profiles() {
    json list = files_in(config_.storage.profiles, {".icc", ".icm"});
    const std::string fallback = fs::absolute(config_.colour.output_profile).string();
    for (json& p : list)
        p["default"] = p["path"] == fallback;
    return list;
}

json DaemonApi::add_design(const std::string& name, const std::string& bytes) {
    const fs::path p = upload(config_.storage.designs, name, bytes, ".tjmap", "design",
                              [](const fs::path& file) { synth::load_texture_map(file.string()); });
    log_line("design " + p.string() + " added over the API");
    return {{"name", name}, {"path", p.string()}};
}

json DaemonApi::add_profile(const std::string& name, const std::string& bytes) {
    const fs::path p = upload(config_.storage.profiles, name, bytes, ".icc", "profile",
                              [this](const fs::path& file) {
                                  colour::ColourSettings c = config_.colour;
                                  c.output_profile = file;
                                  colour::CmykTransform check(c);
                              });
    log_line("profile " + p.string() + " added over the API");
    return {{"name", name}, {"path", p.string()}};
}

json DaemonApi::reload_config() {
    if (kill(getpid(), SIGHUP) != 0) throw std::runtime_error("cannot signal the daemon");
    return {{"reload", "requested"},
            {"note", "[print] takes effect now; other sections after a restart (see the log)"}};
}

}  // namespace tilejet::daemon
