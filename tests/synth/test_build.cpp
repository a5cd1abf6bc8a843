// Building texture maps: what the map holds, and that it looks like its exemplar.

#include <catch2/catch.hpp>
#include <opencv2/imgproc.hpp>

#include "fixtures.hpp"
#include "tilejet/synth/build.hpp"
#include "tilejet/synth/internal/diamond.hpp"
#include "tilejet/synth/sampler.hpp"

using namespace tilejet::synth;
using tilejet::test::demo_exemplar;
using tilejet::test::small_map;

using tilejet::test::mean_lab;

TEST_CASE("a rendered region has the exemplar's mean CIELab colour", "[build]") {
    const cv::Vec3d ex = mean_lab(demo_exemplar());
    const cv::Vec3d out = mean_lab(render_region(small_map(), 8, {12345, -6789, 1024, 1024}));
    const double delta_e = cv::norm(ex - out);  // CIE76
    INFO("exemplar Lab " << ex << ", rendered Lab " << out << ", dE76 " << delta_e);
    REQUIRE(delta_e < 3.0);
}

TEST_CASE("the demo design's map at default settings keeps the exemplar's mean colour",
          "[build][heavy]") {
    // Regression: a cell image chosen for calm over colour made the demo wall 4.9 dE2000 dark.
    const TextureMap map = build_texture_map(demo_exemplar(), BuildParams{});
    const cv::Vec3d ex = mean_lab(demo_exemplar());
    const cv::Vec3d out = mean_lab(render_region(map, 2026, {-4321, 98765, 1536, 1536}));
    const double delta_e = cv::norm(ex - out);  // CIE76
    INFO("exemplar Lab " << ex << ", rendered Lab " << out << ", dE76 " << delta_e);
    REQUIRE(delta_e < 3.0);
}

TEST_CASE("the cell image wraps around without a seam", "[build]") {
    // Across the wrap the cell image should change no more than between any two neighbouring
    // columns or rows inside it: compare the mean jump at the wrap with the typical jump.
    const cv::Mat cell = small_map().cell_images.front().pixels;
    cv::Mat lab;
    cell.convertTo(lab, CV_32FC3, 1.0 / 255);
    cv::cvtColor(lab, lab, cv::COLOR_RGB2Lab);
    auto column_jump = [&](int a, int b) {
        double sum = 0;
        for (int y = 0; y < lab.rows; ++y)
            sum += cv::norm(lab.at<cv::Vec3f>(y, a) - lab.at<cv::Vec3f>(y, b));
        return sum / lab.rows;
    };
    double inner = 0;
    for (int x = 0; x + 1 < lab.cols; ++x)
        inner += column_jump(x, x + 1);
    inner /= lab.cols - 1;
    const double wrap = column_jump(lab.cols - 1, 0);
    INFO("mean jump inside " << inner << ", across the wrap " << wrap);
    REQUIRE(wrap < 2.0 * inner);
}

TEST_CASE("a built map has patches in both sets, inside their diamonds and the source", "[build]") {
    const TextureMap& map = small_map();
    const CellImage& image = map.cell_images.front();
    REQUIRE(image.a.size() > 20);
    REQUIRE(image.b.size() > 20);
    const tilejet::synth::detail::CellGrid grid(map.cell_width, map.cell_height);
    for (const PatchSet* set : {&image.a, &image.b}) {
        size_t small = 0, large = 0;
        for (const Patch& p : set->patches) {
            REQUIRE(p.src_x >= 0);
            REQUIRE(p.src_y >= 0);
            REQUIRE(p.src_x + p.width <= map.source.cols);
            REQUIRE(p.src_y + p.height <= map.source.rows);
            for (int y = 0; y < p.height; ++y)
                for (int x = 0; x < p.width; ++x)
                    if (p.covers(x, y)) REQUIRE(grid.in_diamond_interior(p.x + x, p.y + y));
            const int side = std::max(p.width, p.height);
            small += side <= map.cell_width / 8;
            large += side >= map.cell_width / 4;
        }
        // Sizes span from a few pixels to a good part of the cell.
        REQUIRE(small > 0);
        REQUIRE(large > 0);
    }
}

TEST_CASE("map builds do not depend on the number of threads", "[build][heavy]") {
    BuildParams p;
    p.corner_colours = 2;  // a set: its images and their patches are built on threads too
    p.cell_size = 48;
    p.patches = 12;
    p.candidates = 96;
    p.seed = 4;
    p.threads = 1;
    const TextureMap one = build_texture_map(demo_exemplar(), p);
    p.threads = 2;
    const TextureMap two = build_texture_map(demo_exemplar(), p);
    REQUIRE(one.id == two.id);
    p.seed = 5;
    REQUIRE(build_texture_map(demo_exemplar(), p).id != one.id);
}

TEST_CASE("small exemplars are enlarged into a source twice the cell size", "[build]") {
    cv::Mat small;
    demo_exemplar()(cv::Rect(0, 0, 70, 70)).copyTo(small);
    BuildParams p;
    p.corner_colours = 1;
    p.cell_size = 64;
    p.patches = 40;
    p.candidates = 400;
    const TextureMap map = build_texture_map(small, p);
    REQUIRE(map.source.cols >= 128);
    REQUIRE(map.source.rows >= 128);
}

TEST_CASE("a cell set copies from the exemplar itself, even an exemplar of the cell's size",
          "[build]") {
    // A quilt of a small exemplar keeps its calm parts and loses its large ones: marble's
    // veins became rows of one motif, the demo design's long veins shards. So a set is made
    // from the exemplar as it is whenever it holds a block of the cell's inside (three
    // quarters of the cell) and the strips round it: for cells of 40 px and more, any
    // exemplar the cell fits in (strips longer than the source are quilted from two blocks).
    BuildParams p;
    p.cell_size = 64;
    p.patches = 4;
    p.candidates = 8;
    for (const cv::Size size : {cv::Size(64, 64), cv::Size(96, 80)}) {
        INFO(size.width << "x" << size.height << " px exemplar, 64 px cells");
        cv::Mat exemplar;
        demo_exemplar()(cv::Rect(cv::Point(40, 30), size)).copyTo(exemplar);
        const TextureMap direct = build_texture_map(exemplar, p);
        REQUIRE(direct.cell_images.size() > 1);
        REQUIRE(direct.source.size() == exemplar.size());
        CHECK(cv::norm(direct.source, exemplar, cv::NORM_INF) == 0);
    }
}
