// tilejet map build | map info

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "tilejet/colour/exemplar_profile.hpp"
#include "tilejet/config/section.hpp"
#include "tilejet/config/toml_file.hpp"
#include "tilejet/quality/patch_coverage.hpp"
#include "tilejet/synth/build.hpp"
#include "tilejet/synth/exemplar.hpp"
#include "tilejet/synth/map_file.hpp"

namespace tilejet::cli {

namespace {

// map info's patch coverage is of one fixed region and job seed, so that two maps' figures
// compare: 2048 x 2048 px is 16 x 16 cells of the default size, enough that the share hardly
// depends on the seed, and it takes well under a second.
constexpr synth::Region kCoverageRegion{0, 0, 2048, 2048};
constexpr uint64_t kCoverageSeed = 1;

struct BuildOptions {
    std::string exemplar, output, enlarge = "quilt";
    double exemplar_dpi = 0, dpi = 0;
    std::string config;  // where the line's [render] dpi comes from when --dpi is not given
    synth::BuildParams params;
};

// The print resolution a map is built for: --dpi, else the line's [render] dpi.
double print_dpi(const BuildOptions& o) {
    if (o.dpi > 0) return o.dpi;
    const std::string path = o.config.empty() ? "config/tilejet.toml" : o.config;
    if (o.config.empty() && !std::filesystem::exists(path))
        throw synth::SynthError(
            "map build needs the resolution the design will print at: give --dpi P, or "
            "--config FILE whose [render] dpi it takes (" +
            path + " does not exist here)");
    const toml::table root = config::load_toml_file(path);
    config::ConfigSection render(root["render"].as_table(), {path}, "render");
    return double(render.get_int("dpi", 360, 10, 2400));
}

// A one-line progress meter, only when stderr is a terminal (logs and CI stay clean).
synth::BuildProgress terminal_progress() {
    if (!isatty(STDERR_FILENO)) return {};
    return [](std::string_view stage, size_t done, size_t total) {
        std::fprintf(stderr, "\r  %-18.*s %zu/%zu (%3zu%%)", int(stage.size()), stage.data(), done,
                     total, total ? done * 100 / total : 100);
        if (done == total) std::fputc('\n', stderr);
        std::fflush(stderr);
    };
}

struct PatchCounts {
    size_t a = 0, b = 0;
};

// Over all cell images: each has its own A and B sets.
PatchCounts count_patches(const synth::TextureMap& map) {
    PatchCounts counts;
    for (const synth::CellImage& image : map.cell_images)
        counts.a += image.a.size(), counts.b += image.b.size();
    return counts;
}

void run_build(const BuildOptions& o) {
    const auto start = std::chrono::steady_clock::now();
    const cv::Mat scanned = colour::load_exemplar(o.exemplar);
    // A design has a physical size: the exemplar is resampled once, before anything else, from
    // the resolution it was scanned at to the one it prints at.
    const double exemplar_dpi =
        o.exemplar_dpi > 0 ? o.exemplar_dpi : synth::read_exemplar_dpi(o.exemplar).value_or(0);
    if (exemplar_dpi <= 0)
        throw synth::SynthError(
            "exemplar '" + o.exemplar +
            "' records no resolution: give the pixels per inch it was scanned or photographed "
            "at with --exemplar-dpi D (a 600 mm slab 4724 px across is 200 dpi), or save it with "
            "one (PNG pHYs, JPEG JFIF or Exif, TIFF XResolution)");
    synth::BuildParams params = o.params;
    params.dpi = print_dpi(o);
    params.exemplar_dpi = exemplar_dpi;
    const cv::Mat exemplar =
        synth::resample_exemplar(scanned, exemplar_dpi, params.dpi, o.exemplar);
    const synth::TextureMap map = synth::build_texture_map(exemplar, params, terminal_progress());
    synth::save_texture_map(map, o.output);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const PatchCounts counts = count_patches(map);
    std::printf(
        "wrote %s: map %s, %g dpi (exemplar %g dpi, %dx%d px), cell %dx%d, %zu cell images (%d "
        "corner colours, %d variant%s), %zu A + %zu B patches, %ju bytes, %.1f s\n",
        o.output.c_str(), map.id_hex().substr(0, 16).c_str(), map.build.dpi, map.build.exemplar_dpi,
        map.build.exemplar_width, map.build.exemplar_height, map.cell_width, map.cell_height,
        map.cell_images.size(), map.corner_colours, map.variants, map.variants == 1 ? "" : "s",
        counts.a, counts.b, uintmax_t(std::filesystem::file_size(o.output)), seconds);
}

void run_info(const std::string& path) {
    const synth::TextureMap map = synth::load_texture_map(path);
    const PatchCounts counts = count_patches(map);
    nlohmann::ordered_json j;
    j["map_id"] = map.id_hex();
    j["format_version"] = synth::format_version_of(map);
    j["cell_width"] = map.cell_width;
    j["cell_height"] = map.cell_height;
    j["cell_images"] = map.cell_images.size();
    j["corner_colours"] = map.corner_colours;
    j["variants"] = map.variants;
    if (map.variants > 1) {
        using Rule = synth::TextureMap::VariantRule;
        j["variant_rule"] = map.variant_rule == Rule::parity        ? "parity"
                            : map.variant_rule == Rule::break_twins ? "break twins"
                            : map.variant_rule == Rule::hashed      ? "hashed"
                                                                    : "hashed, plain cells in four";
    }
    j["patches_a"] = counts.a;  // over all cell images
    j["patches_b"] = counts.b;
    j["source_width"] = map.source.cols;
    j["source_height"] = map.source.rows;
    j["bytes"] = std::filesystem::file_size(path);
    // The design's physical size; null for maps built before resolutions were recorded.
    if (map.build.dpi > 0) {
        j["dpi"] = map.build.dpi;
        j["exemplar_dpi"] = map.build.exemplar_dpi;
        j["exemplar_mm"] = {map.build.exemplar_width / map.build.dpi * 25.4,
                            map.build.exemplar_height / map.build.dpi * 25.4};
        // Why the cell is the size it is, in a word.
        char why[64];
        if (map.build.grain > 0)
            std::snprintf(why, sizeof why, "grain %.1f px", map.build.grain);
        else
            std::snprintf(why, sizeof why, "--cell");
        j["cell_from"] = why;
    } else {
        j["dpi"] = nullptr;
    }
    j["patch_coverage"] = quality::patch_coverage(map, kCoverageSeed, kCoverageRegion);
    j["build"] = {{"seed", map.build.seed},
                  {"exemplar_width", map.build.exemplar_width},
                  {"exemplar_height", map.build.exemplar_height},
                  {"patches_requested", map.build.patches_requested},
                  {"candidates", map.build.candidates},
                  {"active_per_cell", map.build.active_per_cell}};
    std::printf("%s\n", j.dump().c_str());
}

}  // namespace

void add_map_commands(CLI::App& app) {
    CLI::App* map = app.add_subcommand("map", "build texture maps and inspect them");
    map->require_subcommand(1);

    auto build = std::make_shared<BuildOptions>();
    CLI::App* b = map->add_subcommand("build", "build a texture map from an exemplar photo");
    b->add_option("EXEMPLAR", build->exemplar, "PNG, JPEG or TIFF exemplar")->required();
    b->add_option("-o,--output", build->output, "texture map file to write")->required();
    b->add_option("--exemplar-dpi", build->exemplar_dpi,
                  "the exemplar's resolution in pixels per inch (default: what its file records; "
                  "required when it records none)")
        ->check(CLI::Range(1.0, 100000.0));
    b->add_option("--dpi", build->dpi,
                  "the resolution the design prints at; the exemplar is resampled to it "
                  "(default: [render] dpi of --config)")
        ->check(CLI::Range(10.0, 2400.0));
    b->add_option("--config", build->config,
                  "config file whose [render] dpi is the default --dpi (default "
                  "config/tilejet.toml)");
    b->add_option("--cell", build->params.cell_size,
                  "cell size in px (default: four of the exemplar's largest structures, 256 to 320 "
                  "px (to 640 px from 1024 px exemplars on), at most the exemplar's side)");
    b->add_option(
        "--corner-colours", build->params.corner_colours,
        "corner colours K: K^4 cell images per variant that meet seamlessly whatever the hash "
        "picks, so no cell image, edge or corner repeats on a grid; 1: one cell image "
        "(default 3 for cells up to 320 px and for slab scans from about 5800 px, where 81 "
        "images still copy less than the exemplar; 4 for exemplars under 128 px; 2 for other "
        "large cells and on a lattice)");
    b->add_option("--variants", build->params.variants,
                  "cell images per combination of corner colours, 1 or 2: with 2 a cell shows "
                  "either by hash, but where a neighbour has its combination the one that parts "
                  "them; plain combinations (one colour at all four corners) get 4, so no two "
                  "neighbours across an edge or a vertex show the same image (default 2, but 1 "
                  "for grain "
                  "under 8 px in cells up to 320 px, and for cells over 320 px from a source "
                  "their set copies less than once)");
    b->add_flag("--smooth-steps", build->params.smooth_steps,
                "spread the tone steps where each cell image's blocks cut into its frame strips "
                "over its insides: no lines along the cell grid, but the copies no longer exact "
                "(texture energy rises; README, session 34)");
    b->add_option(
         "--frame-patches", build->params.frame_patches,
         "in a set off a lattice, frame patches kept per edge of each cell image (on a "
         "grained design, the edges across its grain only): the "
         "edge's strip continued into the cell to a cut of its own, shown by hash, so "
         "the cut along each border lies at another depth in each cell: fewer lines "
         "along the cell grid on grained designs, more texture energy on fine ones "
         "(default 4 on designs with a grain, such as wood, in cells up to 320 px, else 0, none; "
         "README, sessions 35, 43 and 44)")
        ->check(CLI::Range(0, 16));
    b->add_option("--frame-active", build->params.frame_active,
                  "expected frame patches shown per cell (default 8)")
        ->check(CLI::Range(0.0, 64.0));
    b->add_option(
        "--patches", build->params.patches,
        "patches kept per cell image (default 600 for one cell image; in a set none, 32 when "
        "--active is given)");
    b->add_option("--candidates", build->params.candidates,
                  "candidate patches searched per cell image (default 40 per patch, 8 in a set)");
    b->add_option(
        "--active", build->params.active_per_cell,
        "expected active patches per cell, eta * |set| (default 10 for one cell image; none in "
        "a set, 4 there when --patches or --candidates is given)");
    b->add_option("--seed", build->params.seed, "build seed (default 1)");
    b->add_option("--threads", build->params.threads, "threads (default: all cores)");
    b->add_option("--lattice", build->params.lattice,
                  "auto (default): keep a near-regular exemplar's lattice; off")
        ->transform(CLI::CheckedTransformer(
            std::map<std::string, synth::BuildParams::Lattice>{
                {"auto", synth::BuildParams::Lattice::Auto},
                {"off", synth::BuildParams::Lattice::Off}},
            CLI::ignore_case));
    b->add_option("--colour-gain", build->params.colour_gain,
                  "near-regular exemplars: how much the lattice tiles' colours differ, 0 all "
                  "alike, 1 as in the exemplar (default), 2 twice as much");
    b->add_option("--enlarge", build->enlarge,
                  "how an exemplar too small to copy from directly (two cells for one cell "
                  "image or on a lattice; for a set only with cells under 40 px) is enlarged "
                  "into the source: quilt (default), rsgf or enm");
    b->callback([build] {
        build->params.enlarge = synth::parse_synth_method(build->enlarge, "--enlarge");
        run_build(*build);
    });

    auto info_path = std::make_shared<std::string>();
    CLI::App* i = map->add_subcommand("info", "print a texture map's figures as JSON");
    i->add_option("MAP", *info_path, "texture map file")->required();
    i->callback([info_path] { run_info(*info_path); });
}

}  // namespace tilejet::cli
