// tilejet profile build | profile check

#include <cstdio>
#include <memory>

#include "commands.hpp"
#include "tilejet/colour/measurements.hpp"
#include "tilejet/colour/profile_builder.hpp"
#include "tilejet/colour/profile_report.hpp"

namespace tilejet::cli {

namespace {

void print_report(const std::string& profile, const std::string& measurements) {
    const colour::ProfileReport r =
        colour::check_profile(profile, colour::read_measurements(measurements));
    std::printf(
        "{\"profile\":\"%s\",\"measurements\":\"%s\",\"patches\":%zu,"
        "\"delta_e2000\":{\"mean\":%.3f,\"p95\":%.3f,\"max\":%.3f}}\n",
        profile.c_str(), measurements.c_str(), r.patches, r.mean, r.p95, r.max);
}

}  // namespace

void add_profile_commands(CLI::App& app) {
    CLI::App* profile = app.add_subcommand("profile", "build and check the line's ICC profiles");
    profile->require_subcommand(1);

    struct BuildArgs {
        std::string measurements, output;
        colour::ProfileBuildOptions options;
    };
    auto b = std::make_shared<BuildArgs>();
    CLI::App* build = profile->add_subcommand(
        "build", "build a CMYK output profile from fired-tile measurements (ArgyllCMS colprof)");
    build->add_option("MEASUREMENTS", b->measurements, "CGATS .ti3 with CMYK and LAB fields")
        ->required();
    build->add_option("-o,--output", b->output, "ICC profile to write")->required();
    build->add_option("--ink-limit", b->options.ink_limit_percent,
                      "total ink limit, % (default 300)");
    build->add_option("--quality", b->options.quality, "colprof quality l|m|h|u (default m)")
        ->check(CLI::IsMember({"l", "m", "h", "u"}));
    build->add_option("--description", b->options.description, "profile description");
    build->callback([b] {
        colour::build_profile(b->measurements, b->output, b->options);
        print_report(b->output, b->measurements);
    });

    auto c = std::make_shared<std::pair<std::string, std::string>>();
    CLI::App* check = profile->add_subcommand(
        "check", "report CIEDE2000 of a profile against measurements (mean, 95th percentile, max)");
    check->add_option("PROFILE", c->first, "CMYK output profile")->required();
    check->add_option("MEASUREMENTS", c->second, "CGATS .ti3")->required();
    check->callback([c] { print_report(c->first, c->second); });
}

}  // namespace tilejet::cli
