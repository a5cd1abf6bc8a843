// Lattice detection on exemplars with known lattices (made by fixtures.hpp).

#include <catch2/catch.hpp>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <random>

#include "fixtures.hpp"
#include "tilejet/synth/build.hpp"
#include "tilejet/synth/lattice.hpp"
#include "tilejet/synth/sampler.hpp"

using namespace tilejet::synth;

using tilejet::test::Basis;
using tilejet::test::make_lattice_texture;
using tilejet::test::same_lattice;

TEST_CASE("lattices of generated near-regular exemplars are found", "[lattice]") {
    struct Case {
        const char* name;
        Basis truth;
        cv::Size size;
        bool ellipse;
    };
    const Case cases[] = {
        {"running-bond brick", {{40, 0}, {20, 17}}, {233, 191}, false},
        {"square mosaic", {{23, 0}, {0, 23}}, {181, 167}, true},
        {"hexagonal-like mosaic", {{26, 0}, {13, 22.5}}, {205, 189}, true},
        {"sheared lattice", {{29, 6}, {-7, 24}}, {211, 203}, true},
        {"stretched brick", {{52, 0}, {26, 15}}, {250, 170}, false},
    };
    for (const Case& c : cases)
        for (uint32_t seed : {1u, 2u}) {
            const Lattice l =
                detect_lattice(make_lattice_texture(c.truth, c.size, seed, c.ellipse));
            INFO(c.name << " seed " << seed << ": found v1 (" << l.v1.x << "," << l.v1.y << ") v2 ("
                        << l.v2.x << "," << l.v2.y << ") kind " << lattice_kind_name(l.kind)
                        << " score " << l.score);
            REQUIRE(l.kind != LatticeKind::Stochastic);
            REQUIRE(same_lattice(l, c.truth));
            REQUIRE(l.geometry_regularity.has_value());
            REQUIRE(l.appearance_regularity.has_value());
        }
}

TEST_CASE("tile colour variation lowers appearance regularity, not geometry", "[lattice]") {
    const Basis b{{30, 0}, {0, 30}};
    cv::Mat calm = make_lattice_texture(b, {200, 200}, 3, true);
    // The same lattice with strong per-tile colour: repaint each tile's ellipse.
    cv::Mat varied = calm.clone();
    std::mt19937 rng(9);
    for (int ty = 0; ty < 7; ++ty)
        for (int tx = 0; tx < 7; ++tx) {
            const cv::Scalar colour(rng() % 200 + 30, rng() % 200 + 30, rng() % 200 + 30);
            cv::ellipse(varied, cv::Point(tx * 30 + 15, ty * 30 + 15), cv::Size(11, 11), 0, 0, 360,
                        colour, cv::FILLED);
        }
    const Lattice a = detect_lattice(calm), v = detect_lattice(varied);
    REQUIRE(same_lattice(a, b));
    REQUIRE(same_lattice(v, b));
    REQUIRE(*v.appearance_regularity < *a.appearance_regularity - 0.1);
}

TEST_CASE("white noise and marble are stochastic", "[lattice]") {
    cv::Mat noise(200, 200, CV_8UC3);
    cv::randu(noise, 0, 256);
    const Lattice n = detect_lattice(noise);
    REQUIRE(n.kind == LatticeKind::Stochastic);
    REQUIRE(n.v1 == cv::Point(1, 0));
    REQUIRE(n.v2 == cv::Point(0, 1));
    REQUIRE_FALSE(n.geometry_regularity.has_value());

    const Lattice marble = detect_lattice(tilejet::test::demo_exemplar());
    INFO("marble: v1 (" << marble.v1.x << "," << marble.v1.y << ") score " << marble.score);
    REQUIRE(marble.kind == LatticeKind::Stochastic);

    REQUIRE(detect_lattice(cv::Mat(64, 64, CV_8UC3, cv::Scalar(9, 9, 9))).kind ==
            LatticeKind::Stochastic);
}

TEST_CASE("a lattice-aware map keeps the exemplar's lattice at four times its size",
          "[lattice][build][heavy]") {
    const Basis brick{{40, 0}, {20, 17}};
    const cv::Mat exemplar = make_lattice_texture(brick, {233, 191}, 4);
    BuildParams p;
    p.corner_colours = 2;  // a set: every image and strip must keep the courses
    p.patches = 16;
    p.candidates = 128;
    const TextureMap map = build_texture_map(exemplar, p);
    // Cells are a lattice-compatible rectangle: whole courses (34 px) and whole bricks (40 px).
    INFO("cell " << map.cell_width << "x" << map.cell_height);
    REQUIRE(map.cell_width % 40 == 0);
    REQUIRE(map.cell_height % 34 == 0);
    const cv::Mat out = render_region(map, 5, {-3000, 7000, 4 * 233, 4 * 191});
    const Lattice found = detect_lattice(out);
    INFO("rendered: v1 (" << found.v1.x << "," << found.v1.y << ") v2 (" << found.v2.x << ","
                          << found.v2.y << ")");
    REQUIRE(same_lattice(found, brick));

    // Without the lattice the cell period takes over: the check above can fail.
    p.lattice = BuildParams::Lattice::Off;
    const Lattice off = detect_lattice(
        render_region(build_texture_map(exemplar, p), 5, {-3000, 7000, 4 * 233, 4 * 191}));
    REQUIRE_FALSE(same_lattice(off, brick));
}

TEST_CASE("on a lattice plain cells keep two variants", "[lattice][build][heavy]") {
    // Made last, a lattice set's extra variants of plain cells found few lattice windows left
    // that no earlier image had copied to their places: the corpus's brick wall lost texture
    // energy with them (build.cpp). Off a lattice they are made (test_cell_sets.cpp).
    const cv::Mat exemplar = make_lattice_texture({{40, 0}, {20, 17}}, {233, 191}, 4);
    BuildParams p;
    // Two corner colours as on a lattice: off it, a source this small gets three by default
    // (CellSet::default_corner_colours), and the counts below are those of two.
    p.corner_colours = 2;
    p.variants = 2;
    p.patches = 2;
    p.candidates = 2;
    const TextureMap on = build_texture_map(exemplar, p);
    CHECK(on.variants == 2);
    CHECK(on.variant_rule == TextureMap::VariantRule::hashed);
    CHECK(on.cell_images.size() == 32);
    p.lattice = BuildParams::Lattice::Off;
    const TextureMap off = build_texture_map(exemplar, p);
    CHECK(off.variant_rule == TextureMap::VariantRule::plain_in_four);
    CHECK(off.cell_images.size() == 36);
}

TEST_CASE("brick courses with joints anywhere are found, to a fraction of a pixel",
          "[lattice][courses]") {
    for (const double pitch : {16.6, 21.3, 27.0})
        for (const uint32_t seed : {1u, 2u}) {
            const cv::Mat rows = tilejet::test::make_course_texture(pitch, {260, 230}, seed);
            const Lattice l = detect_lattice(rows);
            INFO("pitch " << pitch << " seed " << seed << ": kind " << lattice_kind_name(l.kind)
                          << " found " << l.pitch);
            REQUIRE(l.kind == LatticeKind::Courses);
            REQUIRE(std::abs(l.pitch - pitch) <= 0.25);
            REQUIRE(l.v1 == cv::Point(1, 0));
            REQUIRE(l.v2 == cv::Point(0, int(std::lround(l.pitch))));
            // Courses standing up are found across x.
            cv::Mat columns;
            cv::transpose(rows, columns);
            const Lattice t = detect_lattice(columns);
            REQUIRE(t.kind == LatticeKind::Courses);
            REQUIRE(std::abs(t.pitch - pitch) <= 0.25);
            REQUIRE(t.v1 == cv::Point(0, 1));
        }
    // A two-way lattice stays one, although its rows are courses too.
    const Lattice bond =
        detect_lattice(make_lattice_texture({{40, 0}, {20, 17}}, {233, 191}, 1, false));
    REQUIRE(bond.kind != LatticeKind::Courses);
}

TEST_CASE("laid tiles with two periods in the exemplar are found", "[lattice]") {
    for (const uint32_t seed : {1u, 2u, 3u}) {
        const Basis tiles{{100, 0}, {0, 100}};
        const Lattice l = detect_lattice(make_lattice_texture(tiles, {200, 200}, seed, false));
        INFO("seed " << seed << ": v1 (" << l.v1.x << "," << l.v1.y << ") v2 (" << l.v2.x << ","
                     << l.v2.y << ") kind " << lattice_kind_name(l.kind));
        REQUIRE(l.kind != LatticeKind::Stochastic);
        REQUIRE(same_lattice(l, tiles));
    }
}

namespace {

// How well the mortar rows line up across the vertical cell borders of a render of courses:
// the correlation of the luminance row profiles just left and just right of each border.
double course_continuity(const cv::Mat& rgb, int first_border, int cell_width) {
    cv::Mat grey;
    cv::cvtColor(rgb, grey, cv::COLOR_RGB2GRAY);
    grey.convertTo(grey, CV_64F);
    std::vector<double> left, right;
    for (int xb = first_border; xb + 4 <= grey.cols; xb += cell_width) {
        if (xb < 4) continue;
        for (int y = 0; y < grey.rows; ++y) {
            left.push_back(cv::mean(grey(cv::Rect(xb - 4, y, 4, 1)))[0]);
            right.push_back(cv::mean(grey(cv::Rect(xb, y, 4, 1)))[0]);
        }
    }
    cv::Mat a(left, true), b(right, true);
    cv::Scalar ma, sa, mb, sb;
    cv::meanStdDev(a, ma, sa);
    cv::meanStdDev(b, mb, sb);
    return cv::mean((a - ma[0]).mul(b - mb[0]))[0] / (sa[0] * sb[0]);
}

}  // namespace

TEST_CASE("a map of brick courses keeps the courses running across cells",
          "[lattice][courses][heavy]") {
    const double pitch = 16.6;
    const cv::Mat exemplar = tilejet::test::make_course_texture(pitch, {300, 300}, 5);
    const Lattice truth = detect_lattice(exemplar);
    REQUIRE(truth.kind == LatticeKind::Courses);
    BuildParams p;
    p.corner_colours = 2;
    p.patches = 16;
    p.candidates = 128;
    const TextureMap map = build_texture_map(exemplar, p);
    INFO("cell " << map.cell_width << "x" << map.cell_height);
    // Cells hold whole courses, to within half a pixel.
    const double courses = map.cell_height / pitch;
    REQUIRE(std::abs(courses - std::round(courses)) * pitch <= 0.5);
    const Region region{-3 * map.cell_width, 7 * map.cell_height, 6 * map.cell_width,
                        4 * map.cell_height};
    const cv::Mat out = render_region(map, 5, region);
    const Lattice kept = detect_lattice(out);
    // The score is how far the courses stand out at whole pitches: a course that steps or
    // changes its width at a cell border lowers it.
    INFO("exemplar: courses stand "
         << truth.score << " above; rendered: " << lattice_kind_name(kept.kind) << ", pitch "
         << kept.pitch << ", " << kept.score << " above");
    REQUIRE(kept.kind == LatticeKind::Courses);
    REQUIRE(std::abs(kept.pitch - pitch) <= 0.3);
    REQUIRE(kept.score >= 0.8 * truth.score);
    REQUIRE(course_continuity(out, 0, map.cell_width) >= 0.8);

    // Without the lattice, each cell's courses start where they happen to: they step at the
    // borders, and the check above can fail.
    p.lattice = BuildParams::Lattice::Off;
    const TextureMap free = build_texture_map(exemplar, p);
    const Lattice broken = detect_lattice(
        render_region(free, 5, Region{0, 0, 6 * free.cell_width, 4 * free.cell_height}));
    INFO("without the lattice: " << lattice_kind_name(broken.kind) << ", pitch " << broken.pitch
                                 << ", " << broken.score << " above");
    REQUIRE(broken.score < 0.6 * truth.score);
}

// Slab scans are analysed at most 2048 px across (an FFT of the whole would take gigabytes),
// and their lattice fitted back to the full image to the pixel.
TEST_CASE("the lattice of a slab-scan-sized exemplar is found to the pixel from a smaller copy",
          "[lattice][slab][heavy]") {
    const cv::Size size(4300, 2300);  // analysed 2.1 times smaller
    const Basis brick{{440, 0}, {220, 187}};
    const Lattice l = detect_lattice(make_lattice_texture(brick, size, 5, false));
    INFO("found v1 (" << l.v1.x << "," << l.v1.y << ") v2 (" << l.v2.x << "," << l.v2.y << ") kind "
                      << lattice_kind_name(l.kind));
    REQUIRE(l.kind != LatticeKind::Stochastic);
    CHECK(same_lattice(l, brick, 1.0));

    const double pitch = 61.3;
    const Lattice c = detect_lattice(tilejet::test::make_course_texture(pitch, size, 6));
    REQUIRE(c.kind == LatticeKind::Courses);
    CHECK(c.pitch == Approx(pitch).margin(0.3));
    CHECK(c.v2 == cv::Point(0, 61));
}
