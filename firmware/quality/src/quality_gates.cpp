#include "tilejet/quality/quality_gates.hpp"

#include <sstream>

namespace tilejet::quality {

QualityGates quality_gates(const nlohmann::ordered_json& tilejet,
                           const nlohmann::ordered_json& quilt, double patch_coverage) {
    QualityGates g;
    if (tilejet.contains("periodicity") && tilejet["periodicity"].is_number()) {
        g.periodicity = tilejet["periodicity"].get<double>();
    } else {
        // The wall's highest peak (metrics "periodicity_peak" "value"), or none.
        const auto peak = [](const nlohmann::ordered_json& method) -> std::optional<double> {
            if (!method.contains("periodicity_peak")) return std::nullopt;
            const auto& p = method["periodicity_peak"];
            if (!p.is_object() || !p.contains("value") || !p["value"].is_number())
                return std::nullopt;
            return p["value"].get<double>();
        };
        const std::optional<double> own = peak(tilejet), baseline = peak(quilt);
        if (own && baseline && *baseline > 0) {
            g.periodicity = *own / *baseline;
            g.periodicity_against_quilt_wall = true;
        }
    }
    const double own = tilejet.value("texture_energy", 0.0);
    const double reference = quilt.value("texture_energy", 0.0);
    if (reference > 0) g.texture_energy_vs_quilt = own / reference;
    g.patch_coverage = patch_coverage;
    return g;
}

nlohmann::ordered_json gates_json(const QualityGates& g) {
    auto value = [](const std::optional<double>& v) {
        return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json();
    };
    nlohmann::ordered_json j;
    j["periodicity"] = value(g.periodicity);
    j["periodicity_pass"] = g.periodicity_pass();
    j["periodicity_reference"] = g.periodicity_reference();
    j["texture_energy_vs_quilt"] = value(g.texture_energy_vs_quilt);
    j["texture_energy_pass"] = g.texture_energy_pass();
    j["grid_lines"] = value(g.grid_lines());
    j["grid_lines_pass"] = g.grid_lines_pass();
    j["grid_lines_limit"] = g.grid_lines_limit;
    j["pass"] = g.pass();
    j["limit"] = g.limit;
    j["patch_coverage"] = g.patch_coverage;
    j["cell_border_repeat"] = g.cell_border_repeat;
    j["cell_inside_repeat"] = g.cell_inside_repeat;
    j["coherence_border"] = g.coherence_border;
    j["coherence_inside"] = g.coherence_inside;
    j["quilt_coherence"] = g.quilt_coherence;
    j["light_border"] = g.light_border;
    j["light_inside"] = g.light_inside;
    j["whole_cell_correlation"] = g.whole_cell_correlation;
    j["half_cell_correlation"] = g.half_cell_correlation;
    j["grid_lines_rows"] = value(g.grid_lines_rows);
    j["grid_lines_columns"] = value(g.grid_lines_columns);
    return j;
}

const char* verdict(bool pass) {
    return pass ? "PASS" : "FAIL";
}

std::string gate_figure(const std::optional<double>& v) {
    if (!v) return "n/a";
    std::ostringstream s;
    s.precision(3);
    s << *v;
    return s.str();
}

}  // namespace tilejet::quality
