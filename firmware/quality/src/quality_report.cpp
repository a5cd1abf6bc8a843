#include "tilejet/quality/quality_report.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <stdexcept>

#include "tilejet/quality/wall_comparison.hpp"

namespace tilejet::quality {

namespace {

// Colours of the heat map by the largest repeated window size: 16 px pale to 256 px red.
const cv::Vec3b kHeatColours[] = {{90, 140, 255}, {60, 220, 230}, {250, 230, 60},
                                  {255, 150, 30}, {230, 30, 30},  {160, 0, 90}};

cv::Mat heat_tile(const cv::Mat& rgb, const cv::Mat& heat) {
    cv::Mat grey, out(rgb.size(), CV_8UC3);
    cv::cvtColor(rgb, grey, cv::COLOR_RGB2GRAY);
    for (int y = 0; y < rgb.rows; ++y)
        for (int x = 0; x < rgb.cols; ++x) {
            const uint8_t g = grey.at<uint8_t>(y, x), level = heat.at<uint8_t>(y, x);
            if (level == 0) {
                out.at<cv::Vec3b>(y, x) = {g, g, g};
                continue;
            }
            const cv::Vec3b c = kHeatColours[std::min<int>(level - 1, 5)];
            for (int k = 0; k < 3; ++k)
                out.at<cv::Vec3b>(y, x)[k] = uint8_t(0.35 * g + 0.65 * c[k]);
        }
    return out;
}

// The wall laid out, each tile scaled by `scale` (area averaging) after `paint`.
template <typename Paint>
cv::Mat mosaic(const Wall& wall, double scale, Paint&& paint) {
    const int tw = std::max(1, int(std::lround(wall.tile.width * scale)));
    const int th = std::max(1, int(std::lround(wall.tile.height * scale)));
    cv::Mat out(wall.rows() * th, wall.columns * tw, CV_8UC3, cv::Scalar::all(255));
    for (size_t k = 0; k < wall.tiles.size(); ++k) {
        const cv::Rect at(int(k % size_t(wall.columns)) * tw, int(k / size_t(wall.columns)) * th,
                          tw, th);
        cv::resize(paint(k), out(at), at.size(), 0, 0, cv::INTER_AREA);
    }
    return out;
}

std::string html_escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '<')
            out += "&lt;";
        else if (c == '>')
            out += "&gt;";
        else if (c == '&')
            out += "&amp;";
        else
            out += c;
    }
    return out;
}

const char* kLineColours[] = {"#c0392b", "#2c3e50", "#8e44ad", "#16a085", "#d68910"};

std::string repeat_curve_svg(const ReportPage& page) {
    const double w = 520, h = 260, left = 50, bottom = 30, top = 10, right = 120;
    const size_t n = page.window_sizes.size();
    auto px = [&](size_t i) {
        return left + (n > 1 ? double(i) / double(n - 1) : 0) * (w - left - right);
    };
    auto py = [&](double share) { return top + (1 - share) * (h - top - bottom); };
    std::ostringstream s;
    s << "<svg width='" << w << "' height='" << h << "' class='plot'>";
    for (double v : {0.0, 0.05, 0.25, 0.5, 0.75, 1.0})
        s << "<line x1='" << left << "' x2='" << w - right << "' y1='" << py(v) << "' y2='" << py(v)
          << "' stroke='" << (v == 0.05 ? "#e67e22" : "#ddd") << "'/><text x='4' y='" << py(v) + 4
          << "' font-size='11'>" << v * 100 << "%</text>";
    for (size_t i = 0; i < n; ++i)
        s << "<text x='" << px(i) - 8 << "' y='" << h - 10 << "' font-size='11'>"
          << page.window_sizes[i] << "</text>";
    for (size_t m = 0; m < page.methods.size(); ++m) {
        const auto& curve = page.methods[m].metrics["repeat_curve"];
        s << "<polyline fill='none' stroke-width='2' stroke='" << kLineColours[m % 5]
          << "' points='";
        for (size_t i = 0; i < n; ++i)
            s << px(i) << "," << py(curve[std::to_string(page.window_sizes[i])].get<double>())
              << " ";
        s << "'/><text x='" << w - right + 8 << "' y='" << 20 + 16 * double(m)
          << "' font-size='12' fill='" << kLineColours[m % 5] << "'>" << page.methods[m].name
          << "</text>";
    }
    s << "</svg>";
    return s.str();
}

std::string histogram_svg(const ReportPage& page, int channel, const char* label) {
    const double w = 300, h = 140;
    std::vector<const std::vector<double>*> series{&page.exemplar_colour.channel[size_t(channel)]};
    for (const auto& m : page.methods)
        series.push_back(&m.colour.channel[size_t(channel)]);
    double peak = 1e-9;
    for (const auto* s : series)
        for (double v : *s)
            peak = std::max(peak, v);
    std::ostringstream s;
    s << "<svg width='" << w << "' height='" << h << "' class='plot'><text x='4' y='14' "
      << "font-size='12'>" << label << "</text>";
    for (size_t k = 0; k < series.size(); ++k) {
        const auto& v = *series[k];
        s << "<polyline fill='none' stroke-width='" << (k == 0 ? 3 : 1.5) << "' stroke='"
          << (k == 0 ? "#999" : kLineColours[(k - 1) % 5]) << "' points='";
        for (size_t i = 0; i < v.size(); ++i)
            s << double(i) / double(v.size() - 1) * w << "," << h - 4 - v[i] / peak * (h - 24)
              << " ";
        s << "'/>";
    }
    s << "</svg>";
    return s.str();
}

std::string figure(const nlohmann::ordered_json& v) {
    if (v.is_null()) return "n/a";
    if (v.is_number_float()) {
        std::ostringstream s;
        s.precision(3);
        s << v.get<double>();
        return s.str();
    }
    return v.dump();
}

// The quilt baseline's texture energy, 0 when the page has none.
double quilt_energy(const ReportPage& page) {
    for (const MethodSection& m : page.methods)
        if (m.name == "quilt") return m.metrics.value("texture_energy", 0.0);
    return 0;
}

// The two gates and patch coverage, large, with their verdicts: the first thing on the page.
std::string gates_html(const ReportPage& page) {
    const QualityGates& g = page.gates;
    std::ostringstream h;
    auto gate = [&](const char* label, const std::optional<double>& value, bool pass,
                    const std::string& what) {
        h << "<div class='gate " << (pass ? "pass" : "fail") << "'><div class='label'>" << label
          << "</div><div class='value'>" << gate_figure(value) << " <b>" << verdict(pass)
          << "</b></div><div class='what'>" << what << "</div></div>";
    };
    h << "<h2>Gates: " << verdict(g.pass()) << "</h2><div class='gates'>";
    gate("periodicity", g.periodicity, g.periodicity_pass(),
         std::string("tilejet wall's highest autocorrelation peak, relative to the ") +
             g.periodicity_reference() +
             (g.periodicity_against_quilt_wall
                  ? "'s: the exemplar quilted to the same size has no peak above zero to compare "
                    "with"
                  : " to the same size"));
    gate("texture_energy vs quilt", g.texture_energy_vs_quilt, g.texture_energy_pass(),
         "tilejet's texture energy divided by the quilt baseline's, both ways: the wall's "
         "8x8 neighbourhoods against the exemplar's and the exemplar's against the wall's");
    gate("lines along the cell grid", g.grid_lines(), g.grid_lines_pass(),
         "how much more tilejet's tone changes, blurred to a fortieth of the cell, at its "
         "strongest place in the cell than at any place of an unrelated period, the stronger of "
         "along the rows and along the columns (" +
             gate_figure(g.grid_lines_rows) + " / " + gate_figure(g.grid_lines_columns) +
             "): about 1 where seams lie anywhere; over " + gate_figure(g.grid_lines_limit) +
             " the cells show as squares from a few steps back");
    h << "<div class='gate'><div class='label'>patch coverage</div><div class='value'>"
      << gate_figure(g.patch_coverage * 100)
      << " %</div><div class='what'>share of tilejet's wall showing a patch; the rest shows the "
         "cell image, which repeats with the cell lattice</div></div>"
      << "<div class='gate'><div class='label'>same place of the cell</div><div class='value'>"
      << gate_figure(g.cell_border_repeat * 100) << " % / "
      << gate_figure(g.cell_inside_repeat * 100)
      << " %</div><div class='what'>of tilejet's cells, how many show the same pixel at a place "
         "of the cell: along the cell borders / inside them (the grid a wall folded by the "
         "cell size shows)</div></div>"
      << "<div class='gate'><div class='label'>texture coherence by place</div><div class='value'>"
      << gate_figure(g.coherence_border) << " / " << gate_figure(g.coherence_inside)
      << "</div><div class='what'>tilejet's 8x8 neighbourhoods against the exemplar's (lower is "
         "closer), along the cell borders / inside the cells; the quilt wall's: "
      << gate_figure(g.quilt_coherence)
      << ". The borders are where a cell's inside is cut into the strips it shares with its "
         "neighbours</div></div>"
      << "<div class='gate'><div class='label'>lightest 5 % by place</div><div class='value'>"
      << gate_figure(g.light_border * 100) << " % / " << gate_figure(g.light_inside * 100)
      << " %</div><div class='what'>share of tilejet's plane in its own lightest 5 % (veins "
         "and flecks), along the cell borders / inside the cells: about 5 % each where the "
         "wall shows them anywhere, lower along the borders where calm frames draw the cell "
         "grid</div></div>"
      << "<div class='gate'><div class='label'>correlation at whole cells</div><div "
         "class='value'>"
      << gate_figure(g.whole_cell_correlation) << " / " << gate_figure(g.half_cell_correlation)
      << "</div><div class='what'>tilejet's autocorrelation averaged over every lag of two "
         "cells and more / the same lags half a cell further: what the set repeats at every "
         "lag of the lattice (cell images, strips, places of the cell), under the few chance "
         "repeats that make periodicity's highest peak; about 0 where nothing lines up with the "
         "cells</div></div></div><p>The first two gates pass at "
      << gate_figure(g.limit)
      << " or below (1 = as good as quilting every tile offline), the third at "
      << gate_figure(g.grid_lines_limit) << " or below.</p>";
    return h.str();
}

}  // namespace

void write_rgb_png(const cv::Mat& rgb, const std::filesystem::path& path) {
    cv::Mat bgr;
    cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
    if (!cv::imwrite(path.string(), bgr))
        throw std::runtime_error("cannot write '" + path.string() + "'");
}

void write_wall_pictures(const Wall& wall, const Repetition& repetition,
                         const std::filesystem::path& dir, const std::string& name, int max_side) {
    const cv::Size laid = wall.laid_size();
    const double scale = std::min(1.0, double(max_side) / std::max(laid.width, laid.height));
    write_rgb_png(mosaic(wall, scale, [&](size_t k) { return wall.tiles[k]; }),
                  dir / (name + "-wall.png"));
    write_rgb_png(
        mosaic(wall, scale, [&](size_t k) { return heat_tile(wall.tiles[k], repetition.heat[k]); }),
        dir / (name + "-repeats.png"));
    if (wall.seams.empty() || wall.seams.front().empty()) return;
    // Seams are a pixel wide: shown at full size on a corner of up to 2 x 2 tiles.
    const cv::Rect corner(0, 0, std::min(laid.width, 2 * wall.tile.width),
                          std::min(laid.height, 2 * wall.tile.height));
    cv::Mat picture = wall.laid(corner);
    for (size_t k = 0; k < wall.tiles.size(); ++k) {
        const cv::Point at(int(k % size_t(wall.columns)) * wall.tile.width,
                           int(k / size_t(wall.columns)) * wall.tile.height);
        for (int y = 0; y < wall.tile.height; ++y)
            for (int x = 0; x < wall.tile.width; ++x) {
                const cv::Point p = at + cv::Point(x, y);
                if (!corner.contains(p) || !wall.seams[k].at<uint8_t>(y, x)) continue;
                picture.at<cv::Vec3b>(p) = {255, 0, 200};
            }
    }
    write_rgb_png(picture, dir / (name + "-seams.png"));
}

void write_report_page(const ReportPage& page, const std::filesystem::path& dir) {
    std::ostringstream h;
    h << "<!doctype html><html><head><meta charset='utf-8'><title>" << html_escape(page.title)
      << "</title><style>body{font-family:sans-serif;margin:24px;max-width:1400px}"
         "img{max-width:100%;border:1px solid #ccc}.row{display:flex;gap:16px;flex-wrap:wrap}"
         ".row>div{flex:1;min-width:300px}table{border-collapse:collapse}"
         "td,th{border:1px solid #ccc;padding:4px 8px;text-align:right}"
         "th:first-child,td:first-child{text-align:left}.plot{background:#fafafa}"
         ".gates{display:flex;gap:16px;flex-wrap:wrap}.gate{border:2px solid #999;"
         "padding:8px 16px;min-width:220px;max-width:360px}.gate.pass{border-color:#1e8449}"
         ".gate.fail{border-color:#c0392b}.gate .value{font-size:28px}.gate.pass b{color:#1e8449}"
         ".gate.fail b{color:#c0392b}.gate .what{font-size:12px;color:#555}"
         "</style></head><body><h1>"
      << html_escape(page.title) << "</h1>";
    h << gates_html(page);
    if (!page.side_by_side.empty()) {
        h << "<h2>" << kComparedTiles << "&times;" << kComparedTiles
          << " adjacent tiles, side by side</h2><p>";
        for (size_t k = 0; k < page.side_by_side.size(); ++k)
            h << (k ? ", " : "") << page.side_by_side[k];
        h << ", left to right: the top-left tiles of each wall as they hang next to each other, "
          << "all at " << figure(nlohmann::ordered_json(page.side_by_side_scale * 100))
          << "% of full resolution. Full resolution: ";
        for (size_t k = 0; k < page.side_by_side.size(); ++k)
            h << (k ? ", " : "") << "<a href='wall3x3-" << page.side_by_side[k] << ".png'>"
              << page.side_by_side[k] << "</a>";
        h << ".</p><img src='walls-side-by-side.png'>";
    }
    if (page.has_cell_lines_picture)
        h << "<h2>Where the tilejet wall's tone changes, by place in the cell</h2><p>The tone "
             "change of the lines gate at each pixel of the cell, averaged over every cell: "
             "left between columns (vertical lines), right between rows (horizontal ones); "
             "blue half the median or less, green the median, red twice it or more. Seams that "
             "lie anywhere leave a green speckle; red bands along the borders are cells "
             "outlined by their frame seams.</p><img src='cell-lines.png'>";
    h << "<div class='row'><div><h3>Exemplar</h3><img src='exemplar.png'></div>"
      << "<div><h3>Repeat curve</h3><p>Share of the wall covered by S&times;S windows that occur"
         " verbatim elsewhere on it (orange: the 5% line that sets repeat_scale).</p>"
      << repeat_curve_svg(page) << "</div></div>";
    for (const MethodSection& m : page.methods) {
        h << "<h2>" << m.name << "</h2><p>" << html_escape(m.description) << "</p>"
          << "<div class='row'><div><h3>Wall</h3><img src='" << m.name << "-wall.png'></div>"
          << "<div><h3>Repeated areas</h3><img src='" << m.name << "-repeats.png'><p>Colour: the"
          << " largest repeated window covering the pixel (blue 16 px, cyan 32, yellow 64, "
             "orange 128, red 256); grey: no repeated 16 px window.</p></div>";
        if (m.has_seam_picture)
            h << "<div><h3>Seams (corner of the wall, full size)</h3><img src='" << m.name
              << "-seams.png'></div>";
        h << "</div>";
    }
    h << "<h2>Colour histograms</h2><p>Grey: exemplar; lines: the walls in the colours of the "
         "repeat curve.</p><div class='row'>"
      << histogram_svg(page, 0, "L*") << histogram_svg(page, 1, "a*")
      << histogram_svg(page, 2, "b*") << "</div>";

    h << "<h2>Figures</h2><table><tr><th>metric</th>";
    for (const MethodSection& m : page.methods)
        h << "<th>" << m.name << "</th>";
    h << "</tr>";
    auto row = [&](const std::string& label, auto get) {
        h << "<tr><td>" << label << "</td>";
        for (const MethodSection& m : page.methods)
            h << "<td>" << figure(get(m.metrics)) << "</td>";
        h << "</tr>";
    };
    for (int s : page.window_sizes)
        row("repeat_curve " + std::to_string(s),
            [&](const auto& j) { return j["repeat_curve"][std::to_string(s)]; });
    row("patch_coverage", [](const auto& j) {
        return j.contains("patch_coverage") ? j["patch_coverage"] : nlohmann::ordered_json();
    });
    for (const char* key :
         {"periodicity", "texture_energy", "texture_coherence", "texture_completeness"})
        row(key,
            [&](const auto& j) { return j.contains(key) ? j[key] : nlohmann::ordered_json(); });
    row("texture_energy / quilt's", [&](const auto& j) {
        const double reference = quilt_energy(page);
        return reference > 0
                   ? nlohmann::ordered_json(j["texture_energy"].template get<double>() / reference)
                   : nlohmann::ordered_json();
    });
    for (const char* key : {"repeat_scale", "tile_pairs_sharing"})
        row(key, [&](const auto& j) { return j[key]; });
    row("seam mean (vs exemplar)",
        [](const auto& j) { return j["seam"].is_null() ? j["seam"] : j["seam"]["mean"]; });
    row("seam p99 (vs exemplar)",
        [](const auto& j) { return j["seam"].is_null() ? j["seam"] : j["seam"]["p99"]; });
    for (const char* key : {"mean_delta_e2000", "histogram_distance", "light_tail_share",
                            "dark_tail_share", "out_of_gamut_share", "soft_proof_delta_e2000"})
        row(std::string("colour ") + key, [&](const auto& j) {
            return j["colour"].contains(key) ? j["colour"][key] : nlohmann::ordered_json();
        });
    h << "</table><p>Full figures: <a href='metrics.json'>metrics.json</a>.</p><ul>";
    for (const std::string& f : page.facts)
        h << "<li>" << html_escape(f) << "</li>";
    h << "</ul></body></html>\n";

    const std::filesystem::path path = dir / "index.html";
    std::ofstream out(path, std::ios::trunc);
    out << h.str();
    if (!out) throw std::runtime_error("cannot write '" + path.string() + "'");
}

}  // namespace tilejet::quality
