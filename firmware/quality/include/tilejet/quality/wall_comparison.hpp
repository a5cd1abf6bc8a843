#pragma once

// What a person sees first (issue 16, point 6): a few tiles laid next to each other, for
// tilejet and the methods it replaces, side by side at one scale. A grid, a seam or a repeated
// blob shows at a glance here long before any figure explains it.

#include <filesystem>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "tilejet/quality/wall.hpp"

namespace tilejet::quality {

inline constexpr int kComparedTiles = 3;  // 3 x 3 tiles: the smallest wall that shows a grid

// The top-left `side` x `side` tiles of the laid wall at full resolution: adjacent tiles as
// they hang (in tilejet's wall layout, one contiguous region of the plane). A wall with fewer
// columns or rows gives fewer; missing tiles of a short last row are grey, as in Wall::laid.
cv::Mat wall_corner(const Wall& wall, int side = kComparedTiles);

struct NamedPicture {
    std::string name;  // method: tilejet, canvas, quilt
    cv::Mat rgb;       // CV_8UC3 R,G,B
};

// Writes wall3x3-NAME.png for each picture (full resolution) and walls-side-by-side.png: the
// pictures in one row, in the order given, each under its name, all scaled by the same factor
// so that the largest fits `max_side` px. Returns that factor (1 when none was needed).
double write_walls_side_by_side(const std::vector<NamedPicture>& walls,
                                const std::filesystem::path& dir, int max_side = 768);

}  // namespace tilejet::quality
