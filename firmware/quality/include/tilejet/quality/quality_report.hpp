#pragma once

// The quality report's pictures and page (docs/design.md section 8): pictures first, figures beside
// them. PNGs are written with OpenCV; the plots are inline SVG in index.html.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tilejet/quality/colour_match.hpp"
#include "tilejet/quality/quality_gates.hpp"
#include "tilejet/quality/repetition.hpp"
#include "tilejet/quality/wall.hpp"

namespace tilejet::quality {

// What the page shows of one method (tilejet or a baseline).
struct MethodSection {
    std::string name;         // key in metrics.json: tilejet, canvas, cell, quilt
    std::string description;  // one sentence: how its wall was made
    nlohmann::ordered_json metrics;
    LabStatistics colour;
    bool has_seam_picture = false;
};

// Writes NAME-wall.png (the laid wall, scaled to at most `max_side` px), NAME-repeats.png (the
// same with repeated areas coloured by the largest repeated window size) and, when the wall's
// seams are known, NAME-seams.png (a full-resolution corner of the wall with its seams drawn).
void write_wall_pictures(const Wall& wall, const Repetition& repetition,
                         const std::filesystem::path& dir, const std::string& name,
                         int max_side = 1600);

void write_rgb_png(const cv::Mat& rgb, const std::filesystem::path& path);

struct ReportPage {
    std::string title;
    std::vector<std::string> facts;  // run settings, one line each
    QualityGates gates;              // what the page opens with
    // walls-side-by-side.png (see wall_comparison.hpp): which methods, left to right, and the
    // factor they were scaled by; empty when there is none.
    std::vector<std::string> side_by_side;
    double side_by_side_scale = 1;
    // cell-lines.png (cell_grid_lines() with a picture): where in the cell the tilejet wall's tone
    // changes, for the gate on lines along the cell grid.
    bool has_cell_lines_picture = false;
    LabStatistics exemplar_colour;
    std::vector<MethodSection> methods;
    std::vector<int> window_sizes;
};

// index.html, referring to exemplar.png and the pictures above. It opens with the gates and
// the walls side by side, then the pictures of each method, then the table of every figure.
void write_report_page(const ReportPage& page, const std::filesystem::path& dir);

}  // namespace tilejet::quality
