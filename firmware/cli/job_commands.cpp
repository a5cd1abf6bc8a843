// tilejet job submit | list | show, tilejet pause | resume | stop | ack | status: the daemon's
// JSON API (tilejetd, HTTP), signed in as a user of the daemon's config. tilejet passwd makes
// the password hashes that config holds.
//
// Credentials: --user or $TILEJET_USER; the password from $TILEJET_PASSWORD, else the first
// line of --password-file or $TILEJET_PASSWORD_FILE, else asked for on the terminal.

#include <httplib.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <thread>

#include "commands.hpp"
#include "tilejet/api/access.hpp"
#include "tilejet/api/job_request.hpp"
#include "tilejet/api/password.hpp"

namespace tilejet::cli {

namespace {

using nlohmann::json;

// The daemon's API address: --api, else $TILEJET_API, else the default port on loopback.
std::string api_address(const std::string& option) {
    if (!option.empty()) return option;
    if (const char* env = std::getenv("TILEJET_API")) return env;
    return "127.0.0.1:8470";
}

struct Credentials {
    std::string user, password_file;
};

std::string env(const char* name) {
    const char* v = std::getenv(name);
    return v ? v : "";
}

// One line from a terminal with echo off, so the password never shows on the screen.
std::string ask_password(const std::string& prompt) {
    if (!isatty(STDIN_FILENO)) {
        std::string line;
        if (!std::getline(std::cin, line)) throw std::runtime_error("no password on stdin");
        return line;
    }
    std::fprintf(stderr, "%s", prompt.c_str());
    termios old{};
    tcgetattr(STDIN_FILENO, &old);
    termios quiet = old;
    quiet.c_lflag &= ~tcflag_t(ECHO);
    tcsetattr(STDIN_FILENO, TCSANOW, &quiet);
    std::string line;
    std::getline(std::cin, line);
    tcsetattr(STDIN_FILENO, TCSANOW, &old);
    std::fprintf(stderr, "\n");
    return line;
}

std::string password_for(const Credentials& c, const std::string& user) {
    if (const std::string p = env("TILEJET_PASSWORD"); !p.empty()) return p;
    const std::string file =
        c.password_file.empty() ? env("TILEJET_PASSWORD_FILE") : c.password_file;
    if (!file.empty()) {
        std::ifstream in(file);
        std::string line;
        if (!in || !std::getline(in, line))
            throw std::runtime_error("password file '" + file + "': cannot read it");
        return line;
    }
    if (!isatty(STDIN_FILENO))
        throw std::runtime_error(
            "no password for '" + user +
            "': set TILEJET_PASSWORD or TILEJET_PASSWORD_FILE, or give --password-file");
    return ask_password("password for " + user + ": ");
}

// Signs in at the first request and out again when done: the daemon keeps no session of a
// finished command.
class ApiClient {
  public:
    ApiClient(const std::string& address, Credentials credentials)
        : address_(address), credentials_(std::move(credentials)) {
        const auto colon = address.rfind(':');
        if (colon == std::string::npos)
            throw std::invalid_argument("--api '" + address + "': expected HOST:PORT");
        client_ = std::make_unique<httplib::Client>(address.substr(0, colon),
                                                    std::stoi(address.substr(colon + 1)));
        client_->set_connection_timeout(2, 0);
        client_->set_read_timeout(30, 0);
    }
    ~ApiClient() {
        if (!headers_.empty()) client_->Delete("/api/session", headers_);
    }
    ApiClient(const ApiClient&) = delete;
    ApiClient& operator=(const ApiClient&) = delete;

    json get(const std::string& path) {
        sign_in();
        return check(client_->Get(path.c_str(), headers_), path);
    }
    json post(const std::string& path, const json& body) {
        sign_in();
        return check(client_->Post(path.c_str(), headers_, body.dump(), "application/json"), path);
    }

  private:
    void sign_in() {
        if (!headers_.empty()) return;
        const std::string user =
            credentials_.user.empty() ? env("TILEJET_USER") : credentials_.user;
        if (user.empty())
            throw std::runtime_error("tilejetd wants a user: give --user or set TILEJET_USER");
        const json body{{"user", user}, {"password", password_for(credentials_, user)}};
        const auto r = client_->Post("/api/session", body.dump(), "application/json");
        const json session = check(r, "sign-in as '" + user + "'");
        const std::string cookie = r->get_header_value("Set-Cookie");
        headers_ = {{"Cookie", cookie.substr(0, cookie.find(';'))},
                    {"X-CSRF-Token", session.at("csrf").get<std::string>()}};
    }

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
    Credentials credentials_;
    std::unique_ptr<httplib::Client> client_;
    httplib::Headers headers_;  // the session cookie and CSRF token once signed in
};

struct SubmitArgs {
    std::string map, profile, tile_mm, layout = "scatter";
    std::uint64_t seed = 0;
    std::int64_t tiles = 0;
    int dpi = 0, wall_width = 10, timeout_s = 3600;
    bool wait = false;
};

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

void run_submit(const SubmitArgs& a, const std::string& address, const Credentials& who) {
    const auto [w, h] = api::parse_tile_mm(a.tile_mm, "--tile-mm");
    // The daemon takes designs and profiles from its own folders, by name: a path given here
    // names its file.
    const auto file_name = [](const std::string& p) {
        return std::filesystem::path(p).filename().string();
    };
    json body{{"map", file_name(a.map)}, {"seed", a.seed},     {"tiles", a.tiles},
              {"tile_mm", {w, h}},       {"layout", a.layout}, {"wall_width", a.wall_width}};
    if (a.dpi) body["dpi"] = a.dpi;
    if (!a.profile.empty()) body["profile"] = file_name(a.profile);
    ApiClient api(api_address(address), who);
    const json job = api.post("/api/jobs", body);
    if (!a.wait) {
        std::printf("%s\n", job.dump().c_str());
        return;
    }
    if (!wait_for(api, job["id"].get<std::int64_t>(), a.timeout_s))
        throw std::runtime_error(job["name"].get<std::string>() + " did not complete");
}

void run_list(const std::string& address, const Credentials& who) {
    ApiClient api(api_address(address), who);
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

void run_passwd(const std::string& name, const std::string& role, int iterations) {
    std::string password = ask_password("new password: ");
    if (isatty(STDIN_FILENO) && ask_password("again: ") != password)
        throw std::runtime_error("the passwords differ");
    if (password.size() < 8) throw std::runtime_error("a password needs at least 8 characters");
    const std::string hash = api::hash_password(password, iterations);
    if (name.empty()) {
        std::printf("%s\n", hash.c_str());
        return;
    }
    std::printf("[[users]]\nname = \"%s\"\nrole = \"%s\"\npassword_hash = \"%s\"\n", name.c_str(),
                role.c_str(), hash.c_str());
}

}  // namespace

void add_job_commands(CLI::App& app) {
    auto address = std::make_shared<std::string>();
    auto who = std::make_shared<Credentials>();
    auto add_api_option = [address, who](CLI::App* c) {
        c->add_option("--api", *address,
                      "tilejetd's API HOST:PORT (default $TILEJET_API or "
                      "127.0.0.1:8470)");
        c->add_option("--user", who->user, "sign in as this user (default $TILEJET_USER)");
        c->add_option("--password-file", who->password_file,
                      "the password is this file's first line (default $TILEJET_PASSWORD, "
                      "then $TILEJET_PASSWORD_FILE, then asked for)");
    };

    CLI::App* job = app.add_subcommand("job", "print jobs on the line (tilejetd)");
    job->require_subcommand(1);

    auto s = std::make_shared<SubmitArgs>();
    CLI::App* submit = job->add_subcommand("submit", "queue a job");
    submit
        ->add_option("--map", s->map,
                     "design: a texture map in the daemon's designs folder, by name (a path "
                     "gives its file name)")
        ->required();
    submit->add_option("--seed", s->seed, "job seed")->required();
    submit->add_option("--tiles", s->tiles, "tiles to print")
        ->required()
        ->check(CLI::Range(std::int64_t(1), std::int64_t(10'000'000)));
    submit->add_option("--tile-mm", s->tile_mm, "tile size WxH in mm")->required();
    submit->add_option("--dpi", s->dpi, "resolution; must be the design's (default: the design's)");
    submit->add_option("--profile", s->profile,
                       "CMYK output profile in the daemon's profiles folder, by name (default: "
                       "[colour])");
    submit->add_option("--layout", s->layout, "scatter (default) or wall")
        ->check(CLI::IsMember({"scatter", "wall"}));
    submit->add_option("--wall-width", s->wall_width, "tiles per wall row (wall layout)");
    submit->add_flag("--wait", s->wait, "show progress and wait until the job ends");
    submit->add_option("--timeout", s->timeout_s, "--wait at most this many seconds");
    add_api_option(submit);
    submit->callback([s, address, who] { run_submit(*s, *address, *who); });

    CLI::App* list = job->add_subcommand("list", "jobs, newest first");
    add_api_option(list);
    list->callback([address, who] { run_list(*address, *who); });

    auto id = std::make_shared<std::int64_t>(0);
    CLI::App* show = job->add_subcommand("show", "one job as JSON");
    show->add_option("ID", *id, "job number")->required();
    add_api_option(show);
    show->callback([id, address, who] {
        std::printf("%s\n", ApiClient(api_address(*address), *who)
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
        c->callback([route, address, who] {
            std::printf("%s\n", ApiClient(api_address(*address), *who)
                                    .post("/api/line/" + route, json::object())
                                    .dump()
                                    .c_str());
        });
    }
    CLI::App* status = app.add_subcommand("status", "the line's state as tilejetd sees it");
    add_api_option(status);
    status->callback([address, who] {
        std::printf("%s\n",
                    ApiClient(api_address(*address), *who).get("/api/status").dump(2).c_str());
    });

    struct PasswdArgs {
        std::string name, role = "operator";
        int iterations = api::kPasswordIterations;
    };
    auto p = std::make_shared<PasswdArgs>();
    CLI::App* passwd = app.add_subcommand(
        "passwd",
        "hash a password for tilejetd's config (asked for on a terminal, else stdin's first "
        "line); with NAME, print a whole [[users]] entry");
    passwd->add_option("NAME", p->name, "user name");
    passwd->add_option("--role", p->role, "viewer, operator (default) or engineer")
        ->check(CLI::IsMember(api::role_names()));
    passwd->add_option("--iterations", p->iterations, "PBKDF2 iterations (tests use few)")
        ->check(CLI::Range(1, 10'000'000));
    passwd->callback([p] { run_passwd(p->name, p->role, p->iterations); });
}

}  // namespace tilejet::cli
