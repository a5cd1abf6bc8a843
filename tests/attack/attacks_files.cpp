// Files: racing uploads, an upload past the limit, symlinks at temp names, decompression-bomb
// maps, and jobs that name devices, FIFOs or files outside the designs folder.
#include <fcntl.h>
#include <sys/stat.h>
#include <zlib.h>

#include <barrier>
#include <cstring>
#include <map>

#include "harness.hpp"

namespace tilejet::attack {

namespace {

// The API's limit for an uploaded design or profile (issue 18: "the 16 MB upload limit").
constexpr std::size_t kUploadLimit = std::size_t(16) << 20;

// Every file in the designs folder, dot files included, with its size.
std::map<std::string, std::uintmax_t> listing(const fs::path& folder) {
    std::map<std::string, std::uintmax_t> files;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(folder, ec)) {
        std::error_code size_ec;
        const auto size = e.is_regular_file(size_ec) ? e.file_size(size_ec) : 0;
        files[e.path().filename().string()] = size;
    }
    return files;
}

std::string unique_name(const char* stem) {
    static int counter = 0;
    return std::string(stem) + "-" + std::to_string(::getpid()) + "-" + std::to_string(++counter) +
           ".tjmap";
}

void upload_race(Target& t, const Scale& s, Verdict& v) {
    const auto before = listing(t.designs());
    int bad_rounds = 0;
    for (int round = 0; round < s.race_rounds; ++round) {
        const std::string name = unique_name("race");
        const std::string* bytes[2] = {&t.design_a(), &t.design_b()};
        int status[2] = {-1, -1};
        std::barrier start(2);
        std::vector<std::thread> uploads;
        for (int i = 0; i < 2; ++i)
            uploads.emplace_back([&, i] {
                start.arrive_and_wait();
                status[i] = t.request(t.engineer_session(), "PUT", "/api/designs/" + name,
                                      *bytes[i], seconds(20), "application/octet-stream")
                                .status;
            });
        for (std::thread& u : uploads)
            u.join();
        const int winner = status[0] == 201 ? 0 : 1;
        const bool one_each =
            (status[0] == 201) != (status[1] == 201) && (status[0] == 409 || status[1] == 409);
        const std::string held = read_file(t.designs() / name);
        std::string why;
        if (!one_each)
            why = "answered " + std::to_string(status[0]) + " and " + std::to_string(status[1]);
        else if (held != *bytes[winner])
            why = "the file does not hold the winner's bytes";
        if (!why.empty()) {
            if (++bad_rounds == 1) v.fail("round " + std::to_string(round + 1) + ": " + why);
        }
    }
    if (bad_rounds > 1)
        v.fail(std::to_string(bad_rounds) + " of " + std::to_string(s.race_rounds) +
               " rounds wrong");
    for (const auto& [file, size] : listing(t.designs()))
        v.expect(file.front() != '.' || before.contains(file),
                 "temp file " + file + " left behind");
}

void upload_too_big(Target& t, const Scale& s, Verdict& v) {
    const auto before = listing(t.designs());
    std::atomic<bool> done{false};
    std::atomic<std::uintmax_t> peak{0};
    // What reached the disk while the body was still coming.
    std::thread watch([&] {
        while (!done) {
            std::uintmax_t total = 0;
            for (const auto& [file, size] : listing(t.designs()))
                if (!before.contains(file)) total += size;
            if (total > peak) peak = total;
            std::this_thread::sleep_for(milliseconds(20));
        }
    });
    const std::string name = unique_name("too-big");
    std::string head = "PUT /api/designs/" + name + " HTTP/1.1\r\nHost: " + t.host_header() +
                       "\r\nContent-Type: application/octet-stream\r\n"
                       "Transfer-Encoding: chunked\r\n";
    for (const auto& [header, value] : t.engineer_session())
        head += header + ": " + value + "\r\n";
    head += "\r\n";
    // A valid map first, so that the bytes look like a design until the limit.
    const std::string first = t.design_a();
    std::string first_chunk;
    {
        char size[32];
        std::snprintf(size, sizeof size, "%zx\r\n", first.size());
        first_chunk = size + first + "\r\n";
    }
    const std::string chunk = "10000\r\n" + std::string(0x10000, '\0') + "\r\n";
    const StreamResult r = stream_blob(
        t.port(), head + first_chunk, s.upload_blob, [&](std::size_t) { return chunk; },
        "0\r\n\r\n");
    done = true;
    watch.join();
    v.note(r.how + ", at most " + mib(peak) + " on disk");
    v.expect(!r.finished, "read all " + mib(s.upload_blob) + " without refusing");
    v.expect(r.status != 201, "accepted (201)");
    v.expect(peak <= kUploadLimit,
             mib(peak) + " reached the disk, the limit is " + mib(kUploadLimit));
    for (const auto& [file, size] : listing(t.designs()))
        v.expect(before.contains(file), file + " (" + mib(size) + ") left in the designs folder");
}

void symlinked_temp_names(Target& t, const Scale&, Verdict& v) {
    const fs::path victim = t.dir() / "victim.txt";
    const std::string precious = "a file the daemon may read but must never write\n";
    std::ofstream(victim) << precious;
    const std::string name = unique_name("planted");
    std::vector<fs::path> planted;
    for (const std::string& temp :
         {"." + name + ".upload", "." + name + ".tmp", name + ".tmp", "." + name + ".part",
          name + ".part", name + ".upload", "." + name, "." + name + ".new", name + ".new",
          "." + name + "~"}) {
        const fs::path link = t.designs() / temp;
        fs::create_symlink(victim, link);
        planted.push_back(link);
    }
    const Answer a = t.request(t.engineer_session(), "PUT", "/api/designs/" + name, t.design_a(),
                               seconds(20), "application/octet-stream");
    v.note("upload answered " + std::to_string(a.status));
    v.expect(read_file(victim) == precious, "the symlink's target was overwritten");
    struct stat st {};
    if (::lstat((t.designs() / name).c_str(), &st) == 0) {
        v.expect(S_ISREG(st.st_mode), name + " was published as something else than a file");
        v.expect(read_file(t.designs() / name) == t.design_a(), name + " holds other bytes");
    }
    v.expect(a.status == 201 || a.status == 400 || a.status == 409,
             "upload answered " + std::to_string(a.status));
    for (const fs::path& link : planted) {
        std::error_code ignored;
        fs::remove(link, ignored);
    }
}

// A real map with extra zlib sections that inflate to 256 MiB of zeros each: valid CRCs, a
// valid id (the id hashes the content sections only), 1 MB on disk.
std::string bomb_map(const std::string& map,
                     const std::vector<std::pair<std::string, uint32_t>>& extra) {
    auto le32 = [](const std::string& b, std::size_t at) {
        uint32_t v;
        std::memcpy(&v, b.data() + at, 4);
        return v;
    };
    static const std::string zeros = [] {
        z_stream z{};
        deflateInit(&z, 9);
        std::string out;
        const std::string block(1 << 20, '\0');
        char buffer[1 << 16];
        for (int i = 0; i < 256; ++i) {
            z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(block.data()));
            z.avail_in = uInt(block.size());
            const int flush = i == 255 ? Z_FINISH : Z_NO_FLUSH;
            do {
                z.next_out = reinterpret_cast<Bytef*>(buffer);
                z.avail_out = sizeof buffer;
                deflate(&z, flush);
                out.append(buffer, sizeof buffer - z.avail_out);
            } while (z.avail_out == 0);
        }
        deflateEnd(&z);
        return out;
    }();
    constexpr std::size_t kHeader = 32, kEntry = 32;
    const uint32_t count = le32(map, 12);
    std::string table = map.substr(kHeader, kEntry * count);
    std::string payload = map.substr(kHeader + kEntry * count);
    const std::size_t new_count = count + extra.size();
    const std::size_t shift = kEntry * extra.size();
    // Every old section moves back by the new table entries.
    for (uint32_t i = 0; i < count; ++i) {
        uint64_t offset;
        std::memcpy(&offset, table.data() + i * kEntry + 8, 8);
        offset += shift;
        std::memcpy(table.data() + i * kEntry + 8, &offset, 8);
    }
    const uint32_t crc =
        uint32_t(crc32(0, reinterpret_cast<const Bytef*>(zeros.data()), uInt(zeros.size())));
    uint64_t offset = kHeader + kEntry * new_count + payload.size();
    for (const auto& [tag, index] : extra) {
        std::string e(kEntry, '\0');
        std::memcpy(e.data(), tag.data(), 4);
        const uint32_t stored = uint32_t(zeros.size()), raw = 256u << 20, flags = 1;
        std::memcpy(e.data() + 4, &index, 4);
        std::memcpy(e.data() + 8, &offset, 8);
        std::memcpy(e.data() + 16, &stored, 4);
        std::memcpy(e.data() + 20, &raw, 4);
        std::memcpy(e.data() + 24, &crc, 4);
        std::memcpy(e.data() + 28, &flags, 4);
        table += e;
        payload += zeros;
        offset += zeros.size();
    }
    std::string out = map.substr(0, kHeader);
    const uint32_t count32 = uint32_t(new_count);
    const uint32_t table_crc =
        uint32_t(crc32(0, reinterpret_cast<const Bytef*>(table.data()), uInt(table.size())));
    std::memcpy(out.data() + 12, &count32, 4);
    std::memcpy(out.data() + 16, &offset, 8);
    std::memcpy(out.data() + 24, &table_crc, 4);
    return out + table + payload;
}

// Refused by upload and, put there by hand, refused when a job names it; memory is the monitor's.
void expect_bomb_refused(Target& t, Verdict& v, const std::string& bytes) {
    const std::string name = unique_name("bomb");
    const Answer up = t.request(t.engineer_session(), "PUT", "/api/designs/" + name, bytes,
                                seconds(20), "application/octet-stream");
    v.note(mib(bytes.size()) + " file; upload answered " + std::to_string(up.status));
    v.expect(up.status == 400, "upload answered " + std::to_string(up.status) + ", not 400");
    std::ofstream(t.designs() / name, std::ios::binary) << bytes;
    const Answer job =
        t.request(t.operator_session(), "POST", "/api/jobs", t.job_body(name, 1), seconds(20));
    v.expect(job.status == 400, "job naming it answered " + std::to_string(job.status));
    std::error_code ignored;
    fs::remove(t.designs() / name, ignored);
}

void bomb_unknown_sections(Target& t, const Scale&, Verdict& v) {
    expect_bomb_refused(
        t, v, bomb_map(t.design_a(), {{"JUNK", 0}, {"JUNK", 1}, {"JUNK", 2}, {"JUNK", 3}}));
}

void bomb_unused_sections(Target& t, const Scale&, Verdict& v) {
    // Known tags at indices no map uses: three stay under the loader's 1 GiB for a whole map,
    // so only their being unused gets them refused, and only doing so before inflating them
    // keeps the memory down.
    expect_bomb_refused(t, v, bomb_map(t.design_a(), {{"SRCE", 90}, {"CELL", 91}, {"OVLA", 92}}));
}

// A job naming something that is not a design: refused with 400, promptly.
void bad_design(Target& t, Verdict& v, const std::string& map) {
    const std::string body =
        nlohmann::json{{"map", map}, {"seed", 1}, {"tiles", 1}, {"tile_mm", "200x200"}, {"dpi", 20}}
            .dump();
    const Answer a = t.request(t.operator_session(), "POST", "/api/jobs", body, seconds(3));
    v.note("answered " + (a.status < 0 ? std::string("nothing") : std::to_string(a.status)) +
           " in " + std::to_string(int(a.ms)) + " ms");
    v.expect(a.status == 400,
             "answered " +
                 (a.status < 0 ? std::string("nothing in 3 s") : std::to_string(a.status)) +
                 ", not 400");
    v.expect(a.ms < 2000, "took " + std::to_string(int(a.ms)) + " ms");
}

void dev_zero(Target& t, const Scale&, Verdict& v) {
    bad_design(t, v, "/dev/zero");
}

void fifo(Target& t, const Scale&, Verdict& v) {
    const fs::path path = t.dir() / "design.fifo";
    std::error_code ignored;
    fs::remove(path, ignored);
    if (::mkfifo(path.c_str(), 0644) != 0) throw std::runtime_error("mkfifo failed");
    bad_design(t, v, path.string());
    // A reader stuck in open() waits for a writer: give it one that closes at once, so that a
    // daemon that fell for it gets its thread back for the attacks after this one.
    for (int i = 0; i < 20; ++i) {
        const int fd = ::open(path.c_str(), O_WRONLY | O_NONBLOCK);
        if (fd >= 0) ::close(fd);
        std::this_thread::sleep_for(milliseconds(50));
    }
    fs::remove(path, ignored);
}

void absolute_path(Target& t, const Scale&, Verdict& v) {
    // A valid map outside the designs folder: only its being a path can get it refused.
    bad_design(t, v, fs::absolute(t.maps() / "small.tjmap").string());
}

}  // namespace

std::vector<Attack> file_attacks() {
    return {{"upload-race", upload_race},
            {"upload-chunked-too-big", upload_too_big},
            {"symlinked-temp-names", symlinked_temp_names},
            {"bomb-map-unknown-sections", bomb_unknown_sections},
            {"bomb-map-unused-sections", bomb_unused_sections},
            {"design-dev-zero", dev_zero},
            {"design-fifo", fifo},
            {"design-absolute-path", absolute_path}};
}

}  // namespace tilejet::attack
