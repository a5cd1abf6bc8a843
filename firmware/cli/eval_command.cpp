// tilejet eval: the quality report of a design (docs/design.md section 8, issue 8). Four walls of
// the same tiles: tilejet's, and the baselines canvas (today's factory practice), cell (the
// cell image alone) and quilt (every tile quilted on its own); each measured the same way.

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>

#include "arguments.hpp"
#include "commands.hpp"
#include "tilejet/colour/cmyk_transform.hpp"
#include "tilejet/colour/exemplar_profile.hpp"
#include "tilejet/quality/cell_grid_lines.hpp"
#include "tilejet/quality/cell_place_energy.hpp"
#include "tilejet/quality/cell_place_repeat.hpp"
#include "tilejet/quality/cell_place_tails.hpp"
#include "tilejet/quality/cell_stretch.hpp"
#include "tilejet/quality/colour_match.hpp"
#include "tilejet/quality/patch_coverage.hpp"
#include "tilejet/quality/periodicity.hpp"
#include "tilejet/quality/quality_gates.hpp"
#include "tilejet/quality/quality_report.hpp"
#include "tilejet/quality/repetition.hpp"
#include "tilejet/quality/seam.hpp"
#include "tilejet/quality/soft_proof_check.hpp"
#include "tilejet/quality/texture_energy.hpp"
#include "tilejet/quality/wall.hpp"
#include "tilejet/quality/wall_comparison.hpp"
#include "tilejet/synth/map_file.hpp"
#include "tilejet/synth/quilt.hpp"
#include "tilejet/synth/tile_region.hpp"

namespace tilejet::cli {

namespace {

// Periodicity looks at the top-left corner of the laid wall, this size or eight cells across when
// that is more (lags reach half the window, so a window of 1024 px saw no repeat of a 640 px
// cell), at most the wall: an FFT of a few seconds at most. Four cells until session 38: lags
// under two cells, and neighbouring cells differ by construction, so a set's repeats two and
// three cells apart went unseen (a 256 px granite crop 0.75 with four cells, 2.2 with eight,
// its peak two cells across and one down; the corpus's slate 1.23 three across and two down).
constexpr int kPeriodicityWindow = 1024;
constexpr int kPeriodicityCells = 8;
constexpr size_t kEnergySamples = 30000;
// px of wall the exemplar is looked for in: four times the exemplar's area, at least 1 Mpx and
// at most four times what the index holds whole (so a large exemplar's stretch is indexed on
// every second position, searched at 4 shifts, not every fourth at 16: 30 s less per method
// on the 200-tile bench, whose exemplar is 3.4 Mpx).
constexpr double kCompletenessArea = 1 << 20;
constexpr double kCompletenessMostArea = 4.0 * double(quality::kEnergyMaxPatches);
constexpr double kCanvasMillimetres = 2000;  // the factory canvas: 2 m x 2 m

struct EvalOptions {
    std::string map, output, tile_size, profile, exemplar;
    uint64_t seed = 0;
    int tiles = 200, columns = 0, threads = 0, quilt_block = 0;
    double tile_mm = 600;
};

struct Progress {
    bool on = isatty(STDERR_FILENO);
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
    void say(const std::string& what) const {
        if (!on) return;
        const double s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::fprintf(stderr, "\r\033[K  %6.1f s  %s", s, what.c_str());
        std::fflush(stderr);
    }
    quality::MeasureProgress stage(const std::string& method) const {
        if (!on) return {};
        return [this, method](std::string_view stage, size_t done, size_t total) {
            say(method + ": " + std::string(stage) + " " + std::to_string(done) + "/" +
                std::to_string(total));
        };
    }
    void done() const {
        if (on) std::fputc('\n', stderr);
    }
};

struct Shared {
    cv::Mat exemplar;
    std::unique_ptr<quality::TextureEnergy> energy;
    quality::StepStats exemplar_steps;
    quality::LabStatistics exemplar_colour;
    quality::AutocorrelationPeak reference_peak;
    cv::Size periodicity_window;
    std::optional<colour::CmykTransform> production, colorimetric;
};

nlohmann::ordered_json lab_json(const colour::LabColour& c) {
    return {c.L, c.a, c.b};
}

// Share of tilejet's wall that shows a patch. Every tile has the same size, so it is the mean
// of the tiles' shares; measured on the tiles' own regions of the plane, the same regions
// tilejet_wall renders.
double wall_patch_coverage(const synth::TextureMap& map, const quality::WallSpec& spec) {
    const synth::TileGeometry geometry{spec.tile.width, spec.tile.height, synth::TileLayout::Wall,
                                       spec.columns};
    double sum = 0;
    for (int k = 0; k < spec.tiles; ++k)
        sum += quality::patch_coverage(map, spec.seed,
                                       synth::tile_region(spec.seed, uint64_t(k), geometry));
    return sum / spec.tiles;
}

// What eval prints when done: the gates first, as the page opens, then one line per method.
void print_summary(const quality::ReportPage& page, const std::string& against,
                   const std::filesystem::path& dir) {
    const quality::QualityGates& g = page.gates;
    std::printf("gates (limit %s, 1 = as good as quilting): %s\n",
                quality::gate_figure(g.limit).c_str(), quality::verdict(g.pass()));
    std::printf("  measured against          %s\n", against.c_str());
    const std::string reference = g.periodicity_against_quilt_wall
                                      ? std::string(" (against the ") + g.periodicity_reference() +
                                            "'s peak: the exemplar quilted has none)"
                                      : "";
    std::printf("  periodicity               %-8s %s%s\n",
                quality::gate_figure(g.periodicity).c_str(), quality::verdict(g.periodicity_pass()),
                reference.c_str());
    std::printf("  texture_energy vs quilt   %-8s %s\n",
                quality::gate_figure(g.texture_energy_vs_quilt).c_str(),
                quality::verdict(g.texture_energy_pass()));
    std::printf(
        "  lines along the cell grid %-8s %s (limit %s; along the rows %s, the columns %s)\n",
        quality::gate_figure(g.grid_lines()).c_str(), quality::verdict(g.grid_lines_pass()),
        quality::gate_figure(g.grid_lines_limit).c_str(),
        quality::gate_figure(g.grid_lines_rows).c_str(),
        quality::gate_figure(g.grid_lines_columns).c_str());
    std::printf("  patch coverage            %s %%\n",
                quality::gate_figure(g.patch_coverage * 100).c_str());
    std::printf("  same place of the cell    %s %% along the borders, %s %% inside\n",
                quality::gate_figure(g.cell_border_repeat * 100).c_str(),
                quality::gate_figure(g.cell_inside_repeat * 100).c_str());
    std::printf("  correlation, whole cells  %s at lags of 2 cells and more (%s half a cell off)\n",
                quality::gate_figure(g.whole_cell_correlation).c_str(),
                quality::gate_figure(g.half_cell_correlation).c_str());
    std::printf("  texture coherence         %s along the cell borders, %s inside (quilt: %s)\n",
                quality::gate_figure(g.coherence_border).c_str(),
                quality::gate_figure(g.coherence_inside).c_str(),
                quality::gate_figure(g.quilt_coherence).c_str());
    if (!page.side_by_side.empty())
        std::printf("walls side by side: %s\n", (dir / "walls-side-by-side.png").c_str());
    std::printf("%-8s %11s %14s %12s %18s %10s %11s %10s\n", "method", "periodicity",
                "texture_energy", "repeat_scale", "tile_pairs_sharing", "colour dE", "light tail",
                "dark tail");
    for (const quality::MethodSection& m : page.methods) {
        const auto& j = m.metrics;
        const std::optional<double> periodicity =
            j["periodicity"].is_number() ? std::optional(j["periodicity"].get<double>())
                                         : std::nullopt;
        std::printf(
            "%-8s %11s %14s %12d %18s %10s %10s%% %9s%%\n", m.name.c_str(),
            quality::gate_figure(periodicity).c_str(),
            quality::gate_figure(j["texture_energy"].get<double>()).c_str(),
            j["repeat_scale"].get<int>(),
            quality::gate_figure(j["tile_pairs_sharing"].get<double>()).c_str(),
            quality::gate_figure(j["colour"]["mean_delta_e2000"].get<double>()).c_str(),
            quality::gate_figure(j["colour"]["light_tail_share"].get<double>() * 100).c_str(),
            quality::gate_figure(j["colour"]["dark_tail_share"].get<double>() * 100).c_str());
    }
    std::printf(
        "(tails: share of the wall beyond the exemplar's lightest and darkest %g %%; "
        "%g %% each where the wall keeps the stone's extremes)\n",
        quality::kTailShare * 100, quality::kTailShare * 100);
}

quality::MethodSection measure(const std::string& name, const std::string& description,
                               const quality::Wall& wall, const Shared& shared,
                               const EvalOptions& o, const std::filesystem::path& dir,
                               const Progress& progress) {
    quality::MethodSection section{name, description, {}, {}, false};
    nlohmann::ordered_json& j = section.metrics;
    const quality::Repetition rep =
        quality::measure_repetition(wall, o.threads, progress.stage(name));
    nlohmann::ordered_json curve = nlohmann::ordered_json::object();
    for (const quality::RepeatPoint& p : rep.curve)
        curve[std::to_string(p.size)] = p.share;
    j["repeat_curve"] = curve;
    j["repeat_scale"] = rep.scale;
    j["tile_pairs_sharing"] = rep.tile_pairs_sharing;
    j["shared_window"] = {rep.shared_window.width, rep.shared_window.height};

    progress.say(name + ": periodicity");
    const quality::AutocorrelationPeak peak = quality::autocorrelation_peak(
        wall.laid(cv::Rect(cv::Point(0, 0), shared.periodicity_window)));
    if (shared.reference_peak.value > 0)
        j["periodicity"] = peak.value / shared.reference_peak.value;
    else
        j["periodicity"] = nullptr;  // the exemplar's quilt has no correlation peak at all
    j["periodicity_peak"] = {
        {"value", peak.value},
        {"lag", {peak.lag.x, peak.lag.y}},
        {"exemplar_quilt_value", shared.reference_peak.value},
        {"exemplar_quilt_lag", {shared.reference_peak.lag.x, shared.reference_peak.lag.y}}};

    progress.say(name + ": texture energy");
    // Both ways (texture_energy.hpp): the wall's neighbourhoods against the exemplar's, and
    // the exemplar's against those of a stretch of wall a few times the exemplar's area.
    const double coherence = shared.energy->measure(wall.tiles, kEnergySamples, o.seed);
    const double area =
        std::clamp(4.0 * double(shared.exemplar.total()), kCompletenessArea, kCompletenessMostArea);
    std::vector<cv::Mat> stretch;
    for (double indexed = 0; indexed < area && stretch.size() < wall.tiles.size();) {
        stretch.push_back(wall.tiles[stretch.size()]);
        indexed += double(stretch.back().total());
    }
    const double completeness = quality::TextureEnergy(stretch, o.threads)
                                    .measure({shared.exemplar}, kEnergySamples, o.seed);
    j["texture_energy"] = (coherence + completeness) / 2;
    j["texture_coherence"] = coherence;
    j["texture_completeness"] = completeness;

    progress.say(name + ": seams");
    const quality::SeamStats seams = quality::measure_seams(wall, shared.exemplar_steps, o.threads);
    if (seams.known)
        j["seam"] = {{"mean", seams.mean_ratio},
                     {"p99", seams.p99_ratio},
                     {"delta_e_mean", seams.seam.mean},
                     {"delta_e_p99", seams.seam.p99},
                     {"seam_share", seams.seam_share}};
    else
        j["seam"] = nullptr;
    section.has_seam_picture = seams.known;

    progress.say(name + ": colour");
    section.colour = quality::lab_statistics(wall.tiles, o.threads);
    const quality::ColourMatch colour =
        quality::compare_colour(shared.exemplar_colour, section.colour);
    j["colour"] = {{"mean_delta_e2000", colour.mean_delta_e2000},
                   {"histogram_distance", colour.histogram_distance},
                   {"light_tail_share", colour.light_tail},
                   {"dark_tail_share", colour.dark_tail},
                   {"exemplar_mean_lab", lab_json(colour.exemplar_mean)},
                   {"wall_mean_lab", lab_json(colour.wall_mean)}};
    if (shared.production) {
        progress.say(name + ": soft proof");
        const quality::SoftProofFigures f =
            quality::check_soft_proof(wall, *shared.production, *shared.colorimetric);
        j["colour"]["out_of_gamut_share"] = f.out_of_gamut_share;
        j["colour"]["soft_proof_delta_e2000"] = f.proof_delta_e2000_mean;
        j["colour"]["soft_proof_delta_e2000_p95"] = f.proof_delta_e2000_p95;
    }

    progress.say(name + ": pictures");
    quality::write_wall_pictures(wall, rep, dir, name);
    return section;
}

void run_eval(const EvalOptions& o) {
    const Progress progress;
    const Size2 tile = parse_size(o.tile_size, "--tile-size");
    if (o.tiles < 1) throw std::invalid_argument("--tiles must be at least 1");
    const std::filesystem::path dir = o.output;
    std::filesystem::create_directories(dir);

    progress.say("loading");
    const synth::TextureMap map = synth::load_texture_map(o.map);
    Shared shared;
    // The map keeps its source, which is the exemplar itself whenever the exemplar was large
    // enough (docs/design.md section 2.3; else a quilted enlargement of it): --exemplar says
    // for sure.
    shared.exemplar = o.exemplar.empty() ? map.source : colour::load_exemplar(o.exemplar);
    const bool source_is_exemplar = o.exemplar.empty() &&
                                    map.source.cols == map.build.exemplar_width &&
                                    map.source.rows == map.build.exemplar_height;
    if (!o.profile.empty()) {
        colour::ColourSettings settings;
        settings.output_profile = o.profile;
        shared.production.emplace(settings);
        settings.intent = colour::Intent::RelativeColorimetric;
        shared.colorimetric.emplace(settings);
    }
    const int block =
        o.quilt_block > 0
            ? o.quilt_block
            : synth::quilt_block_for_cell(std::min(shared.exemplar.cols, shared.exemplar.rows));

    quality::WallSpec spec{o.tiles, {tile.width, tile.height}, o.columns, o.seed, o.threads};
    if (spec.columns <= 0) spec.columns = int(std::ceil(std::sqrt(double(o.tiles))));
    const int rows = (o.tiles + spec.columns - 1) / spec.columns;
    const int periodicity_side =
        std::max(kPeriodicityWindow, kPeriodicityCells * std::max(map.cell_width, map.cell_height));
    shared.periodicity_window = {std::min(periodicity_side, spec.columns * tile.width),
                                 std::min(periodicity_side, rows * tile.height)};

    progress.say("exemplar: patch index, statistics, periodicity reference");
    shared.energy = std::make_unique<quality::TextureEnergy>(shared.exemplar, o.threads);
    shared.exemplar_steps = quality::neighbour_steps(shared.exemplar);
    shared.exemplar_colour = quality::lab_statistics({shared.exemplar}, o.threads);
    shared.reference_peak = quality::autocorrelation_peak(
        synth::quilt_texture(shared.exemplar, shared.periodicity_window, o.seed ^ 0x9e71ull, block)
            .rgb);
    quality::write_rgb_png(shared.exemplar, dir / "exemplar.png");

    const cv::Size canvas(int(std::lround(kCanvasMillimetres / o.tile_mm * tile.width)),
                          int(std::lround(kCanvasMillimetres / o.tile_mm * tile.width)));
    quality::ReportPage page;
    page.window_sizes = quality::repeat_window_sizes({tile.width, tile.height});
    page.exemplar_colour = shared.exemplar_colour;
    std::vector<quality::NamedPicture> corners;  // tilejet, canvas, quilt: the walls side by side
    auto run = [&](const std::string& name, const std::string& what, auto make) {
        progress.say(name + ": making the wall");
        const quality::Wall wall = make();
        page.methods.push_back(measure(name, what, wall, shared, o, dir, progress));
        if (name != "cell") corners.push_back({name, quality::wall_corner(wall)});
    };
    run("tilejet",
        "tilejet: tiles 0.." + std::to_string(o.tiles - 1) + " of job seed " +
            std::to_string(o.seed) + " in the wall layout, " + std::to_string(spec.columns) +
            " tiles wide.",
        [&] { return quality::tilejet_wall(map, spec); });
    run("canvas",
        "canvas: one " + std::to_string(canvas.width) + "x" + std::to_string(canvas.height) +
            " px canvas (2 m x 2 m at " + std::to_string(int(o.tile_mm)) +
            " mm per tile width) quilted once from the exemplar, every tile cropped from it at a "
            "random position.",
        [&] { return quality::canvas_wall(shared.exemplar, spec, canvas, block); });
    run("cell", "cell: the map's cell image repeated over the same tile regions, no patches.",
        [&] { return quality::cell_wall(map, spec); });
    run("quilt", "quilt: every tile quilted on its own from the exemplar (the offline reference).",
        [&] { return quality::quilt_wall(shared.exemplar, spec, block); });
    auto section = [&](const std::string& name) -> nlohmann::ordered_json& {
        for (quality::MethodSection& m : page.methods)
            if (m.name == name) return m.metrics;
        throw std::logic_error("no " + name + " wall in the report");
    };
    progress.say("tilejet: patch coverage");
    const double coverage = wall_patch_coverage(map, spec);
    {
        // Coverage first in tilejet's section: it is what its periodicity mostly depends on.
        nlohmann::ordered_json& tilejet = section("tilejet");
        nlohmann::ordered_json first{{"patch_coverage", coverage}};
        for (auto& [key, value] : tilejet.items())
            first[key] = value;
        tilejet = first;
    }
    page.gates = quality::quality_gates(section("tilejet"), section("quilt"), coverage);
    progress.say("tilejet: the same place of the cell");
    const quality::CellPlaceRepeat fold = quality::cell_place_repeat(map, spec.seed);
    section("tilejet")["cell_place_repeat"] = {{"border", fold.border},
                                               {"inside", fold.inside},
                                               {"band_px", fold.band},
                                               {"cells", fold.cells}};
    page.gates.cell_border_repeat = fold.border, page.gates.cell_inside_repeat = fold.inside;
    progress.say("tilejet: texture coherence by place in the cell");
    const cv::Mat place_plane = quality::cell_place_plane(map, spec.seed, o.threads);
    const cv::Size cell(map.cell_width, map.cell_height);
    const quality::CellPlaceEnergy place = quality::cell_place_energy(
        place_plane, cell, *shared.energy, kEnergySamples / 2, spec.seed);
    section("tilejet")["cell_place_energy"] = {
        {"border", place.border}, {"inside", place.inside}, {"band_px", place.band}};
    progress.say("tilejet: the stone's extremes by place in the cell");
    const quality::CellPlaceTails tails = quality::cell_place_tails(place_plane, cell);
    section("tilejet")["cell_place_tails"] = {{"border_light", tails.border_light},
                                              {"inside_light", tails.inside_light},
                                              {"border_dark", tails.border_dark},
                                              {"inside_dark", tails.inside_dark},
                                              {"band_px", tails.band}};
    page.gates.light_border = tails.border_light, page.gates.light_inside = tails.inside_light;
    progress.say("tilejet: lines along the cell grid");
    const cv::Mat stretch =
        quality::cell_stretch_plane(map, spec.seed, quality::kWideStretch, o.threads);
    cv::Mat lines_picture;
    const quality::CellGridLines lines = quality::cell_grid_lines(stretch, cell, &lines_picture);
    quality::write_rgb_png(lines_picture, dir / "cell-lines.png");
    page.has_cell_lines_picture = true;
    section("tilejet")["cell_grid_lines"] = {{"rows", lines.rows},
                                             {"columns", lines.columns},
                                             {"row_at", lines.row_at},
                                             {"column_at", lines.column_at}};
    page.gates.grid_lines_rows = lines.rows, page.gates.grid_lines_columns = lines.columns;
    progress.say("tilejet: correlation at lags of whole cells");
    const quality::CellLagCorrelation lag = quality::cell_lag_correlation(stretch, cell);
    section("tilejet")["cell_lag_correlation"] = {
        {"whole_cells", lag.whole_cells}, {"half_cells", lag.half_cells}, {"lags", lag.lags}};
    page.gates.whole_cell_correlation = lag.whole_cells;
    page.gates.half_cell_correlation = lag.half_cells;
    page.gates.coherence_border = place.border, page.gates.coherence_inside = place.inside;
    page.gates.quilt_coherence = section("quilt").value("texture_coherence", 0.0);
    progress.say("walls side by side");
    page.side_by_side_scale = quality::write_walls_side_by_side(corners, dir);
    for (const quality::NamedPicture& c : corners)
        page.side_by_side.push_back(c.name);
    progress.done();

    // metrics.json opens with the gates, as the page does; then every method's figures.
    nlohmann::ordered_json metrics;
    metrics["gates"] = quality::gates_json(page.gates);
    for (const quality::MethodSection& m : page.methods)
        metrics[m.name] = m.metrics;
    {
        const std::filesystem::path path = dir / "metrics.json";
        std::ofstream out(path, std::ios::trunc);
        out << metrics.dump(2) << "\n";
        if (!out) throw std::runtime_error("cannot write '" + path.string() + "'");
    }
    page.title = "tilejet quality report: " + std::filesystem::path(o.map).filename().string() +
                 ", seed " + std::to_string(o.seed) + ", " + std::to_string(o.tiles) +
                 " tiles of " + o.tile_size;
    // Said with the gates too: measured against a quilted enlargement, they cannot see what
    // the quilt lost (docs/design.md section 2.3).
    const std::string against =
        o.exemplar.empty()
            ? std::string(source_is_exemplar ? "the map's source, which is the exemplar itself"
                                             : "the map's source, a quilted enlargement of the "
                                               "exemplar (pass --exemplar for the original)")
            : o.exemplar;
    page.facts = {
        "map " + map.id_hex().substr(0, 16) + ", cell " + std::to_string(map.cell_width) + "x" +
            std::to_string(map.cell_height) + ", exemplar: " + against,
        "quilting (canvas, quilt, periodicity reference) with " + std::to_string(block) +
            " px blocks",
        "periodicity: highest autocorrelation peak at lags of 16 px or more over the wall's "
        "top-left " +
            std::to_string(shared.periodicity_window.width) + "x" +
            std::to_string(shared.periodicity_window.height) +
            " px, divided by the same for the exemplar quilted to that size",
        "texture energy: the mean of coherence (" + std::to_string(kEnergySamples) +
            " random 8x8 patches of the wall, RMS CIELab distance per pixel to the nearest "
            "exemplar patch) and completeness (as many of the exemplar, to the nearest patch of "
            "a stretch of wall of 4 times its area or 1 Mpx at least): a wall that repeats one "
            "calm corner of the exemplar is coherent but not complete",
        "patch coverage: share of the tilejet wall's pixels (every tile's own region of the "
        "plane) that show a patch rather than the cell image",
        "repeat curve: every window position hashed (2D polynomial hash modulo 2^61-1); equal "
        "hashes count as identical",
    };
    if (!o.profile.empty())
        page.facts.push_back("profile " + o.profile +
                             ": out of gamut = relative colorimetric "
                             "round trip moves the colour by more than CIEDE2000 3; soft proof "
                             "with perceptual intent, 300% ink limit");
    quality::write_report_page(page, dir);
    print_summary(page, against, dir);
    std::printf("wrote %s/index.html and metrics.json\n", dir.string().c_str());
}

}  // namespace

void add_eval_commands(CLI::App& app) {
    auto o = std::make_shared<EvalOptions>();
    CLI::App* eval = app.add_subcommand("eval",
                                        "quality report: repetition, periodicity, texture, seams, "
                                        "colour, against the canvas, cell and quilt baselines");
    eval->add_option("MAP", o->map, "texture map file")->required();
    eval->add_option("--seed", o->seed, "job seed")->required();
    eval->add_option("--tiles", o->tiles, "tiles on the wall (default 200)")
        ->check(CLI::Range(1, 100000));
    eval->add_option("--tile-size", o->tile_size, "tile size WxH in px")->required();
    eval->add_option("--profile", o->profile, "the line's CMYK ICC profile: gamut and soft proof");
    eval->add_option("--exemplar", o->exemplar,
                     "the design's exemplar (default: the map's source)");
    eval->add_option("--columns", o->columns, "tiles per wall row (default: about square)")
        ->check(CLI::Range(0, 100000));
    eval->add_option("--tile-mm", o->tile_mm, "tile width in mm, for the 2 m canvas (default 600)")
        ->check(CLI::Range(10.0, 5000.0));
    eval->add_option("--quilt-block", o->quilt_block,
                     "quilting block in px for the baselines (default: exemplar side / 4)")
        ->check(CLI::Range(0, 4096));
    eval->add_option("--threads", o->threads, "threads (default: all cores)")
        ->check(CLI::Range(0, 1024));
    eval->add_option("-o,--output", o->output, "report directory")->required();
    eval->callback([o] { run_eval(*o); });
}

}  // namespace tilejet::cli
