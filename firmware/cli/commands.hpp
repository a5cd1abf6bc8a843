#pragma once

#include <CLI/CLI.hpp>

namespace tilejet::cli {

// Each group of subcommands registers itself on the top-level app; the action runs from the
// subcommand's callback and throws on failure (main reports the message and exits non-zero).
void add_map_commands(CLI::App& app);
void add_render_commands(CLI::App& app);
void add_profile_commands(CLI::App& app);
void add_analyze_commands(CLI::App& app);
void add_line_commands(CLI::App& app);
void add_sim_commands(CLI::App& app);
void add_job_commands(CLI::App& app);
void add_eval_commands(CLI::App& app);   // tilejet eval: the quality report
void add_synth_commands(CLI::App& app);  // tilejet synth: the offline synthesizers

}  // namespace tilejet::cli
