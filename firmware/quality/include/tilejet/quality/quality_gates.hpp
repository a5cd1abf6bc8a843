#pragma once

// The quality report's gates (issue 16, point 5): a wall must not look like a grid
// (periodicity against the quilted reference) and must look like the exemplar as closely as
// quilting does (texture energy against the quilt baseline). The report opens with them because
// they are what decides whether a design is fit to print; every other figure explains them.
// A third since session 32: no lines along the cell grid (cell_grid_lines.hpp). Walls that
// passed both showed their cells as squares at half size (marble, limestone, slate, wood), a
// grid whose seams differ from cell to cell, so that autocorrelation does not find it.

#include <algorithm>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace tilejet::quality {

// Both figures are ratios to quilting, so one limit serves both: 20 % worse than the offline
// reference is what the issue allows.
inline constexpr double kGateLimit = 1.2;
// Lines along the cell grid, against the wall's own unevenness: at 1.06-1.13 (the corpus's
// gravel, setts, terrazzo) no line shows at half size; at 1.24 and more (limestone, marble,
// slate, wood before session 32) the cells show as squares.
inline constexpr double kGridLinesLimit = 1.15;

struct QualityGates {
    double limit = kGateLimit;
    // tilejet's periodicity (already relative to the exemplar quilted to the same size). When
    // that reference has no autocorrelation peak above zero (a slab scan enlarged 32 times is
    // all slow tone over the window: its highest local maximum -0.05), a ratio to it means
    // nothing, and tilejet's wall's highest peak is taken against the quilting baseline wall's
    // instead (`periodicity_against_quilt_wall`); empty when neither has a peak above zero.
    std::optional<double> periodicity;
    bool periodicity_against_quilt_wall = false;
    // What periodicity is relative to, as metrics.json, the summary and the page name it.
    const char* periodicity_reference() const {
        return periodicity_against_quilt_wall ? "quilting baseline wall" : "exemplar quilted";
    }
    // tilejet's texture energy divided by the quilt baseline's; empty if quilt's is zero.
    std::optional<double> texture_energy_vs_quilt;
    // Share of tilejet's wall covered by shown patches: not a gate, but what the gates depend
    // on most (whatever no patch covers repeats with the cell lattice).
    double patch_coverage = 0;
    // Not gates either: per place of the cell, the share of cells showing the same pixel there,
    // in the band along the cell borders and inside it (cell_place_repeat.hpp): the grid a wall
    // folded by the cell size shows. Set by eval after quality_gates().
    double cell_border_repeat = 0, cell_inside_repeat = 0;
    // Nor these: tilejet's texture coherence along the cell borders and inside the cells
    // (cell_place_energy.hpp), and the quilt wall's over the whole wall, to compare with. Set
    // by eval; 0 when not measured.
    double coherence_border = 0, coherence_inside = 0, quilt_coherence = 0;
    // Nor these: the share of tilejet's plane in its own lightest 5 %, along the cell borders
    // and inside (cell_place_tails.hpp): calm lines along the cells where the border's is the
    // lower. Set by eval; 0 when not measured.
    double light_border = 0, light_inside = 0;
    // Nor these: tilejet's autocorrelation averaged over the lags of whole cells, two cells and
    // more, and the same half a cell further (periodicity.hpp, cell_lag_correlation()): what the
    // set repeats at every lag of the lattice, under the chance repeats that make periodicity's
    // highest peak; about 0 where nothing lines up with the cells. Set by eval.
    double whole_cell_correlation = 0, half_cell_correlation = 0;
    // And a gate: how much more the tone of tilejet's plane changes at its strongest place of the
    // cell than elsewhere, along the rows and the columns (cell_grid_lines.hpp): 1 where no line
    // follows the cell borders. Set by eval after quality_gates().
    // The gate is on the stronger of the two. Empty when not measured.
    std::optional<double> grid_lines_rows, grid_lines_columns;
    double grid_lines_limit = kGridLinesLimit;

    // A figure that could not be measured does not pass: the report cannot vouch for it.
    bool periodicity_pass() const { return periodicity && *periodicity <= limit; }
    bool texture_energy_pass() const {
        return texture_energy_vs_quilt && *texture_energy_vs_quilt <= limit;
    }
    bool grid_lines_pass() const {
        return grid_lines_rows && grid_lines_columns && *grid_lines_rows <= grid_lines_limit &&
               *grid_lines_columns <= grid_lines_limit;
    }
    std::optional<double> grid_lines() const {
        if (!grid_lines_rows || !grid_lines_columns) return {};
        return std::max(*grid_lines_rows, *grid_lines_columns);
    }
    bool pass() const { return periodicity_pass() && texture_energy_pass() && grid_lines_pass(); }
};

// From the metrics.json sections of tilejet and of the quilt baseline (see eval_command.cpp).
QualityGates quality_gates(const nlohmann::ordered_json& tilejet,
                           const nlohmann::ordered_json& quilt, double patch_coverage);

// metrics.json's "gates" object.
nlohmann::ordered_json gates_json(const QualityGates& gates);

// "PASS" or "FAIL".
const char* verdict(bool pass);

// A figure with three significant digits, or "n/a".
std::string gate_figure(const std::optional<double>& v);

}  // namespace tilejet::quality
