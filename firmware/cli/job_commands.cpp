// tilejet job submit | list | show, tilejet pause | resume | stop | ack | status: the daemon's
// JSON API (tilejetd, loopback HTTP).

#include <httplib.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <thread>

#include "commands.hpp"
#include "tilejet/api/job_request.hpp"

namespace tilejet::cli {

namespace {

using nlohmann::json;

// The daemon's API address: --api, else $TILEJET_API, else the default port on loopback.
std::string api_address(const std::string& option) {
    if (!option.empty()) return option;
    if (const char* env = std::getenv("TILEJET_API")) return env;
    return "127.0.0.1:8470";
}

class ApiClient {
  public:
    explicit ApiClient(const std::string& address) : address_(address) {
        const auto colon = address.rfind(':');
        if (colon == std::string::npos)
            throw std::invalid_argument("--api '" + address + "': expected HOST:PORT");
        client_ = std::make_unique<httplib::Client>(address.substr(0, colon),
                                                    std::stoi(address.substr(colon + 1)));
        client_->set_connection_timeout(2, 0);
        client_->set_read_timeout(30, 0);
    }

    json get(const std::string& path) { return check(client_->Get(path.c_str()), path); }
    json post(const std::string& path, const json& body) {
        return check(client_->Post(path.c_str(), body.dump(), "application/json"), path);
    }

  private:
    json check(const httplib::Result& r, const std::string& path) {
        if (!r)
            throw std::runtime_error("tilejetd at " + address_ + " is not answering (" +
                                     httplib::to_string(r.error()) + ")");
        json j = json::parse(r->body, nullptr, false);
        if (r->status >= 300) {
            const std::string message =
                j.is_object() && j.contains("error") ? j["error"].get<std::string>() : r->body;
            throw std::runtime_error(path + ": " + message + " (HTTP " + std::to_string(r->status) +
                                     ")");
        }
        return j;
    }

    std::string address_;
    std::unique_ptr<httplib::Client> client_;
};

struct SubmitArgs {
    std::string map, profile, tile_mm, layout = "scatter";
    std::uint64_t seed = 0;
    std::int64_t tiles = 0;
    int dpi = 0, wall_width = 10, timeout_s = 3600;
    bool wait = false;
};

std::string absolute(const std::string& path) {
    return std::filesystem::absolute(path).lexically_normal().string();
}

// One line per change; rewritten in place on a terminal.
void print_progress(const json& job) {
    static std::string last;
    char text[256];
    std::snprintf(text, sizeof text,
                  "%s: %s, %lld/%lld printed, %lld spoiled, %lld line tiles missed",
                  job["name"].get<std::string>().c_str(), job["status"].get<std::string>().c_str(),
                  (long long)job["printed"], (long long)job["tiles"], (long long)job["spoiled"],
                  (long long)job["missed_line_tiles"]);
    if (text == last) return;
    last = text;
    if (isatty(STDERR_FILENO))
        std::fprintf(stderr, "\r%s   ", text);
    else
        std::fprintf(stderr, "%s\n", text);
}

// Waits for the job to end; true when it is done.
bool wait_for(ApiClient& api, std::int64_t id, int timeout_s) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(timeout_s);
    while (true) {
        const json job = api.get("/api/jobs/" + std::to_string(id));
        print_progress(job);
        const std::string status = job["status"];
        if (status == "done" || status == "failed" || status == "cancelled") {
            if (isatty(STDERR_FILENO)) std::fprintf(stderr, "\n");
            if (status != "done")
                std::fprintf(stderr, "%s %s: %s\n", job["name"].get<std::string>().c_str(),
                             status.c_str(), job["message"].get<std::string>().c_str());
            std::printf("%s\n", job.dump().c_str());
            return status == "done";
        }
        if (std::chrono::steady_clock::now() > deadline) {
            std::fprintf(stderr, "\n");
            throw std::runtime_error("job " + std::to_string(id) + " not finished after " +
                                     std::to_string(timeout_s) + " s");
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(300));
    }
}

void run_submit(const SubmitArgs& a, const std::string& address) {
    const auto [w, h] = api::parse_tile_mm(a.tile_mm, "--tile-mm");
    json body{{"map", absolute(a.map)}, {"seed", a.seed},     {"tiles", a.tiles},
              {"tile_mm", {w, h}},      {"layout", a.layout}, {"wall_width", a.wall_width}};
    if (a.dpi) body["dpi"] = a.dpi;
    if (!a.profile.empty()) body["profile"] = absolute(a.profile);
    ApiClient api(api_address(address));
    const json job = api.post("/api/jobs", body);
    if (!a.wait) {
        std::printf("%s\n", job.dump().c_str());
        return;
    }
    if (!wait_for(api, job["id"].get<std::int64_t>(), a.timeout_s))
        throw std::runtime_error(job["name"].get<std::string>() + " did not complete");
}

void run_list(const std::string& address) {
    ApiClient api(api_address(address));
    std::printf("%-8s %-10s %12s %8s %8s  %s\n", "job", "status", "printed", "spoiled", "missed",
                "map");
    for (const json& j : api.get("/api/jobs")) {
        const std::string printed = std::to_string(j["printed"].get<long long>()) + "/" +
                                    std::to_string(j["tiles"].get<long long>());
        std::printf("%-8s %-10s %12s %8lld %8lld  %s\n", j["name"].get<std::string>().c_str(),
                    j["status"].get<std::string>().c_str(), printed.c_str(),
                    (long long)j["spoiled"], (long long)j["missed_line_tiles"],
                    j["map"].get<std::string>().c_str());
    }
}

}  // namespace

void add_job_commands(CLI::App& app) {
    auto address = std::make_shared<std::string>();
    auto add_api_option = [address](CLI::App* c) {
        c->add_option("--api", *address,
                      "tilejetd's API HOST:PORT (default $TILEJET_API or "
                      "127.0.0.1:8470)");
    };

    CLI::App* job = app.add_subcommand("job", "print jobs on the line (tilejetd)");
    job->require_subcommand(1);

    auto s = std::make_shared<SubmitArgs>();
    CLI::App* submit = job->add_subcommand("submit", "queue a job");
    submit->add_option("--map", s->map, "texture map file")->required();
    submit->add_option("--seed", s->seed, "job seed")->required();
    submit->add_option("--tiles", s->tiles, "tiles to print")
        ->required()
        ->check(CLI::Range(std::int64_t(1), std::int64_t(10'000'000)));
    submit->add_option("--tile-mm", s->tile_mm, "tile size WxH in mm")->required();
    submit->add_option("--dpi", s->dpi, "resolution (default: [render] dpi)");
    submit->add_option("--profile", s->profile, "CMYK output profile (default: [colour])");
    submit->add_option("--layout", s->layout, "scatter (default) or wall")
        ->check(CLI::IsMember({"scatter", "wall"}));
    submit->add_option("--wall-width", s->wall_width, "tiles per wall row (wall layout)");
    submit->add_flag("--wait", s->wait, "show progress and wait until the job ends");
    submit->add_option("--timeout", s->timeout_s, "--wait at most this many seconds");
    add_api_option(submit);
    submit->callback([s, address] { run_submit(*s, *address); });

    CLI::App* list = job->add_subcommand("list", "jobs, newest first");
    add_api_option(list);
    list->callback([address] { run_list(*address); });

    auto id = std::make_shared<std::int64_t>(0);
    CLI::App* show = job->add_subcommand("show", "one job as JSON");
    show->add_option("ID", *id, "job number")->required();
    add_api_option(show);
    show->callback([id, address] {
        std::printf("%s\n", ApiClient(api_address(*address))
                                .get("/api/jobs/" + std::to_string(*id))
                                .dump(2)
                                .c_str());
    });

    const std::pair<const char*, const char*> commands[] = {
        {"pause", "stop the conveyor after the tile under the heads"},
        {"resume", "print again"},
        {"stop", "stop the current job (the tiles in the heads are printed first)"},
        {"ack", "acknowledge a released e-stop"}};
    for (const auto& [name, help] : commands) {
        CLI::App* c = app.add_subcommand(name, help);
        add_api_option(c);
        const std::string route = std::string(name) == "ack" ? "acknowledge" : name;
        c->callback([route, address] {
            std::printf("%s\n", ApiClient(api_address(*address))
                                    .post("/api/line/" + route, json::object())
                                    .dump()
                                    .c_str());
        });
    }
    CLI::App* status = app.add_subcommand("status", "the line's state as tilejetd sees it");
    add_api_option(status);
    status->callback([address] {
        std::printf("%s\n", ApiClient(api_address(*address)).get("/api/status").dump(2).c_str());
    });
}

}  // namespace tilejet::cli
