#include <catch2/catch.hpp>
#include <cstdlib>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "tilejet/quality/cell_grid_lines.hpp"

using namespace tilejet;

namespace {

// Grey-green grain without a place of its own: smoothed white noise, the same every run.
cv::Mat grain(int side) {
    cv::Mat noise(side, side, CV_32FC3);
    cv::RNG rng(12345);
    rng.fill(noise, cv::RNG::NORMAL, cv::Scalar::all(0), cv::Scalar::all(1));
    cv::GaussianBlur(noise, noise, {0, 0}, 3.0);
    cv::Mat plane;
    noise.convertTo(plane, CV_8UC3, 60.0, 128.0);
    return plane;
}

// `plane` with the inside of every cell, `inset` px in from its borders, lighter or darker by up
// to `tone` (one offset a cell): cells outlined as a frame seam outlines them.
cv::Mat outlined(const cv::Mat& plane, int cell, int inset, int tone) {
    cv::Mat out = plane.clone();
    cv::RNG rng(777);
    for (int j = 0; j < plane.rows / cell; ++j)
        for (int i = 0; i < plane.cols / cell; ++i) {
            const cv::Rect inside(i * cell + inset, j * cell + inset, cell - 2 * inset,
                                  cell - 2 * inset);
            out(inside) += cv::Scalar::all(rng.uniform(-tone, tone + 1));
        }
    return out;
}

}  // namespace

TEST_CASE("lines along the cell grid: a plane whose tone changes anywhere shows none",
          "[quality]") {
    const cv::Mat plane = grain(2048);
    for (const int cell : {128, 200}) {
        const quality::CellGridLines lines = quality::cell_grid_lines(plane, {cell, cell});
        INFO("cell " << cell << ": rows " << lines.rows << ", columns " << lines.columns);
        CHECK(lines.rows < 1.1);
        CHECK(lines.columns < 1.1);
    }
}

TEST_CASE("lines along the cell grid: cells outlined by a tone step show where the step lies",
          "[quality]") {
    // Cells of 128 px on 16 x 16 cells (as eval measures), insides within +-24 of the frame's
    // tone.
    const int cell = 128, inset = 8;
    const cv::Mat plane = outlined(grain(2048), cell, inset, 24);
    const quality::CellGridLines lines = quality::cell_grid_lines(plane, {cell, cell});
    INFO("rows " << lines.rows << " at " << lines.row_at << ", columns " << lines.columns << " at "
                 << lines.column_at);
    CHECK(lines.rows > 1.3);
    CHECK(lines.columns > 1.3);
    // The steps lie between the inset's last frame pixel and the inside, on either side.
    const auto at_a_step = [&](int at) {
        return std::abs(at - (inset - 1)) <= 2 || std::abs(at - (cell - inset - 1)) <= 2;
    };
    CHECK(at_a_step(lines.row_at));
    CHECK(at_a_step(lines.column_at));
    // Outlined only along the rows (the steps across the columns smoothed away), the columns
    // show none.
    cv::Mat rows_only = plane.clone();
    for (int y = 0; y < plane.rows; ++y)
        cv::blur(plane.row(y), rows_only.row(y), {cell, 1}, {-1, -1}, cv::BORDER_REFLECT);
    const quality::CellGridLines r = quality::cell_grid_lines(rows_only, {cell, cell});
    INFO("rows only: rows " << r.rows << ", columns " << r.columns);
    CHECK(r.rows > 1.3);
    CHECK(r.columns < 1.1);
}

TEST_CASE("lines along the cell grid: a plane smaller than two cells, or not R,G,B, is refused",
          "[quality]") {
    CHECK_THROWS(quality::cell_grid_lines(cv::Mat(), {32, 32}));
    CHECK_THROWS(quality::cell_grid_lines(cv::Mat(63, 64, CV_8UC3, cv::Scalar::all(0)), {32, 32}));
    CHECK_THROWS(quality::cell_grid_lines(cv::Mat(64, 64, CV_8UC1, cv::Scalar::all(0)), {32, 32}));
    CHECK_THROWS(quality::cell_grid_lines(cv::Mat(64, 64, CV_8UC3, cv::Scalar::all(0)), {1, 32}));
}

TEST_CASE("lines along the cell grid, the picture: red where the cells are outlined, not inside",
          "[quality]") {
    const int cell = 128, inset = 8;
    cv::Mat picture;
    quality::cell_grid_lines(outlined(grain(2048), cell, inset, 24), {cell, cell}, &picture);
    // Two panels of the cell enlarged to 256 px, 8 px apart.
    REQUIRE(picture.type() == CV_8UC3);
    REQUIRE(picture.rows == 256);
    REQUIRE(picture.cols == 2 * 256 + 8);
    const auto redness = [&](int x, int y) {
        const cv::Vec3b p = picture.at<cv::Vec3b>(y, x);  // R, G, B
        return int(p[0]) - int(p[2]);
    };
    // Left panel (changes between columns): the step at column inset - 1 is red at mid-height,
    // the middle of the cell is not; right panel (between rows): the step at row inset - 1.
    const int step = (inset - 1) * 2 + 1, middle = cell;
    INFO("left panel: step " << redness(step, middle) << ", middle " << redness(middle, middle));
    CHECK(redness(step, middle) > 100);
    CHECK(redness(middle, middle) < redness(step, middle) - 100);
    INFO("right panel: step " << redness(256 + 8 + middle, step) << ", middle "
                              << redness(256 + 8 + middle, middle));
    CHECK(redness(256 + 8 + middle, step) > 100);
    CHECK(redness(256 + 8 + middle, middle) < redness(256 + 8 + middle, step) - 100);
}

TEST_CASE("lines along the cell grid, the picture: grain without a place shows no red band",
          "[quality]") {
    const int cell = 128;
    cv::Mat picture;
    quality::cell_grid_lines(grain(2048), {cell, cell}, &picture);
    REQUIRE(picture.cols == 2 * 256 + 8);
    // No column of the left panel, and no row of the right, red along most of its length.
    const auto reddest = [&](bool rows) {
        int worst = 0;
        for (int line = 0; line < 256; ++line) {
            int red = 0;
            for (int along = 0; along < 256; ++along) {
                const cv::Vec3b p = rows ? picture.at<cv::Vec3b>(line, 264 + along)
                                         : picture.at<cv::Vec3b>(along, line);
                red += p[0] > 200 && p[2] < 100;
            }
            worst = std::max(worst, red);
        }
        return worst;
    };
    const int worst_column = reddest(false), worst_row = reddest(true);
    INFO("reddest column " << worst_column << " px of 256, reddest row " << worst_row);
    CHECK(worst_column < 128);
    CHECK(worst_row < 128);
    CHECK_THROWS(quality::cell_grid_lines(cv::Mat(), {32, 32}, &picture));
}
