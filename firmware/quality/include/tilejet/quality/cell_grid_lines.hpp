#pragma once

// Lines along the cell grid: how much more a wall's tone changes at one place of the cell than
// at the others. A cell set's images meet their frame strips along a seam a few pixels inside
// every cell border; where the inside and the strip differ in tone, every cell is outlined, and
// a wall zoomed out shows squares, a grid that neither periodicity (the seams' contents differ
// from cell to cell) nor texture energy (a seam is a few pixels of many) sees. Seen in session
// 32 on marble and limestone at half size, on maps that passed both gates.
//
// Measured as a person sees it from a few steps back: the plane blurred to the scale of a
// fortieth of the cell, the size of its tone change from one row to the next averaged over each
// row, folded by the row's place in the cell; the strongest place against the typical one. The
// same folded by an unrelated period (a row's place in a span of 0.77 cells, so no place of the
// cell lines up from one span to the next) gives the wall's own unevenness, and the figure is
// the one against the other: 1 where seams lie anywhere, more where they line up with the cells.

#include <opencv2/core/mat.hpp>

namespace tilejet::quality {

struct CellGridLines {
    // The strongest place in the cell against the wall's own unevenness, for the lines that run
    // along the rows (horizontal, from tone changes between rows) and the columns.
    double rows = 0, columns = 0;
    // Where they lie: px below the cell's top border, right of its left border (a line between
    // the last row of a cell and the first of the next lies at the cell's height less one).
    int row_at = 0, column_at = 0;
    double worst() const { return rows > columns ? rows : columns; }
};

// `plane`: CV_8UC3 R,G,B, its top-left pixel a cell corner, at least two cells each way; eval
// measures a map's kWideStretch (cell_stretch.hpp).
// With `picture`, also where in the cell those lines lie, drawn there (CV_8UC3 R,G,B): the same
// blurred tone change, between columns on the left (vertical lines) and between rows on the
// right (horizontal ones), at each pixel of the cell averaged over every cell of `plane`, over
// the panel's median: blue half of it or less, green the median, red twice it or more. A wall
// whose seams lie anywhere is a speckle of green; frame seams draw red bands along the borders,
// joints that every image shares draw lines inside.
CellGridLines cell_grid_lines(const cv::Mat& plane, cv::Size cell, cv::Mat* picture = nullptr);

}  // namespace tilejet::quality
