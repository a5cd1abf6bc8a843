// tilejet: the command line for texture maps, tiles and (later) the line and its jobs.

#include <cstdio>
#include <exception>

#include "commands.hpp"

int main(int argc, char** argv) {
    CLI::App app{"tilejet: print-controller tools for a ceramic-tile inkjet line"};
    app.require_subcommand(1);
    tilejet::cli::add_map_commands(app);
    tilejet::cli::add_render_commands(app);
    tilejet::cli::add_profile_commands(app);
    tilejet::cli::add_analyze_commands(app);
    tilejet::cli::add_line_commands(app);
    tilejet::cli::add_sim_commands(app);
    tilejet::cli::add_job_commands(app);
    tilejet::cli::add_eval_commands(app);
    tilejet::cli::add_synth_commands(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tilejet: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
