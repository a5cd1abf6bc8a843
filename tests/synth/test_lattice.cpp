// Lattice detection on exemplars with known lattices, made here.

#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <opencv2/imgproc.hpp>
#include <random>

#include "fixtures.hpp"
#include "tilejet/synth/build.hpp"
#include "tilejet/synth/lattice.hpp"
#include "tilejet/synth/sampler.hpp"

using namespace tilejet::synth;

namespace {

struct Basis {
    cv::Point2d t1, t2;
};

// A near-regular texture on lattice (t1, t2): each tile a rounded "brick" or "stone" (an
// ellipse filling most of the tile) in mortar, every tile with its own colour shift, plus
// per-pixel colour noise, cropped to `size` (not a whole number of periods).
cv::Mat make_lattice_texture(Basis b, cv::Size size, uint32_t seed, bool ellipse = false) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0, 6), tile_shift(0, 14);
    std::map<std::pair<int, int>, cv::Vec3d> tile_colour;
    const double det = b.t1.x * b.t2.y - b.t1.y * b.t2.x;
    cv::Mat out(size, CV_8UC3);
    for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x) {
            // Lattice coordinates of the pixel: solve x = u t1 + v t2.
            const double u = (x * b.t2.y - y * b.t2.x) / det, v = (y * b.t1.x - x * b.t1.y) / det;
            const int iu = int(std::floor(u)), iv = int(std::floor(v));
            const double fu = u - iu, fv = v - iv;
            auto [it, fresh] = tile_colour.try_emplace({iu, iv});
            if (fresh) it->second = {tile_shift(rng), tile_shift(rng), tile_shift(rng)};
            bool inside;
            if (ellipse) {
                const double du = (fu - 0.5) / 0.42, dv = (fv - 0.5) / 0.42;
                inside = du * du + dv * dv < 1;
            } else {
                inside = fu > 0.08 && fu < 0.92 && fv > 0.1 && fv < 0.9;
            }
            const cv::Vec3d base =
                inside ? cv::Vec3d(170, 80, 60) + it->second : cv::Vec3d(200, 200, 190);
            cv::Vec3b& px = out.at<cv::Vec3b>(y, x);
            for (int c = 0; c < 3; ++c)
                px[c] = cv::saturate_cast<uint8_t>(base[c] + noise(rng));
        }
    return out;
}

// Whether every detected vector is (within tol px) a lattice point of the truth and the two
// lattices have the same cell area: then they are the same lattice up to sign, swap and adding
// one vector to the other.
bool same_lattice(const Lattice& found, Basis truth, double tol = 1.5) {
    auto on_truth = [&](cv::Point v) {
        for (int a = -4; a <= 4; ++a)
            for (int b = -4; b <= 4; ++b) {
                const cv::Point2d p = a * truth.t1 + b * truth.t2;
                if (std::hypot(p.x - v.x, p.y - v.y) <= tol) return true;
            }
        return false;
    };
    const double true_area = std::abs(truth.t1.x * truth.t2.y - truth.t1.y * truth.t2.x);
    return on_truth(found.v1) && on_truth(found.v2) &&
           std::abs(found.area() - true_area) < 0.1 * true_area;
}

}  // namespace

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
          "[lattice][build]") {
    const Basis brick{{40, 0}, {20, 17}};
    const cv::Mat exemplar = make_lattice_texture(brick, {233, 191}, 4);
    BuildParams p;
    p.patches = 80;
    p.candidates = 1200;
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
