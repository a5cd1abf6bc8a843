#include <algorithm>
#include <catch2/catch.hpp>
#include <opencv2/core.hpp>

#include "../synth/fixtures.hpp"
#include "tilejet/quality/cell_place_tails.hpp"

using namespace tilejet;

TEST_CASE("the stone's extremes by place: what lies along the cell borders is counted there",
          "[quality]") {
    // 4 x 4 cells of 60 px (band 6 px): white within the band of every border, black inside.
    const int cell = 60, band = 6;
    cv::Mat plane(4 * cell, 4 * cell, CV_8UC3, cv::Scalar::all(0));
    for (int y = 0; y < plane.rows; ++y)
        for (int x = 0; x < plane.cols; ++x) {
            const int u = x % cell, v = y % cell;
            if (u < band || v < band || u >= cell - band || v >= cell - band)
                plane.at<cv::Vec3b>(y, x) = cv::Vec3b(255, 255, 255);
        }
    const quality::CellPlaceTails r = quality::cell_place_tails(plane, {cell, cell}, 90.0, 10.0);
    CHECK(r.band == band);
    CHECK(r.border_light == 1.0);
    CHECK(r.inside_light == 0.0);
    CHECK(r.border_dark == 0.0);
    CHECK(r.inside_dark == 1.0);
    // Shifted by half a cell the white lines cross the cells' middles, and reach the borders
    // only where they cross them: 12 px of each 60 px border band, against 12 of 48 inside.
    cv::Mat shifted;
    cv::Mat(plane, cv::Rect(cell / 2, cell / 2, 3 * cell, 3 * cell)).copyTo(shifted);
    const quality::CellPlaceTails s = quality::cell_place_tails(shifted, {cell, cell}, 90.0, 10.0);
    INFO("shifted: light " << s.border_light << " / " << s.inside_light);
    CHECK(s.border_light < 0.25);
    CHECK(s.inside_light > 0.4);
}

TEST_CASE("the stone's extremes by place: the exemplar itself holds its tails everywhere",
          "[quality]") {
    // The exemplar cut into cells holds about 5 % of its own lightest and darkest 5 % along the
    // borders and inside alike: no place of a cell is calmer.
    const cv::Mat& exemplar = test::demo_exemplar();
    const int cell = exemplar.cols / 4;
    const quality::CellPlaceTails r = quality::cell_place_tails(exemplar, {cell, cell});
    INFO("light " << r.border_light << " / " << r.inside_light << ", dark " << r.border_dark
                  << " / " << r.inside_dark);
    for (const double share : {r.border_light, r.inside_light, r.border_dark, r.inside_dark}) {
        CHECK(share > 0.02);
        CHECK(share < 0.09);
    }
    // With calm frames (every pixel within a tenth of the cell of a border drawn most of the
    // way to the mean colour) the extremes lie inside, as on a wall whose cell borders show.
    cv::Mat calm = exemplar.clone();
    const cv::Scalar mean = cv::mean(exemplar);
    const int band = cell / 10;
    for (int y = 0; y < calm.rows; ++y)
        for (int x = 0; x < calm.cols; ++x) {
            const int u = x % cell, v = y % cell;
            if (std::min({u, v, cell - 1 - u, cell - 1 - v}) >= band) continue;
            cv::Vec3b& p = calm.at<cv::Vec3b>(y, x);
            for (int ch = 0; ch < 3; ++ch)
                p[ch] = uchar((p[ch] + 3 * mean[ch]) / 4);
        }
    const quality::CellPlaceTails c = quality::cell_place_tails(calm, {cell, cell});
    INFO("calm frames: light " << c.border_light << " / " << c.inside_light << ", dark "
                               << c.border_dark << " / " << c.inside_dark);
    CHECK(c.border_light < 0.01);
    CHECK(c.inside_light > 0.06);
    CHECK(c.border_dark < 0.01);
    CHECK(c.inside_dark > 0.06);
}

TEST_CASE("the stone's extremes by place: no cells or no plane is refused", "[quality]") {
    CHECK_THROWS(quality::cell_place_tails(cv::Mat(), {32, 32}, 90.0, 10.0));
    CHECK_THROWS(quality::cell_place_tails(cv::Mat(64, 64, CV_8UC3, cv::Scalar::all(0)), {0, 32},
                                           90.0, 10.0));
    CHECK_THROWS(quality::cell_place_tails(cv::Mat(64, 64, CV_8UC1, cv::Scalar::all(0)), {32, 32},
                                           90.0, 10.0));
    CHECK_THROWS(quality::cell_place_tails(cv::Mat(), {32, 32}));
}
