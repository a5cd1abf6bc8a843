// The offline synthesizers (quilt, rsgf, enm) on exemplars with known lattices and on marble.

#include <catch2/catch.hpp>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <set>

#include "fixtures.hpp"
#include "tilejet/synth/error.hpp"
#include "tilejet/synth/internal/enm.hpp"
#include "tilejet/synth/internal/rsgf.hpp"
#include "tilejet/synth/lattice.hpp"
#include "tilejet/synth/synthesize.hpp"

using namespace tilejet::synth;
using tilejet::test::Basis;
using tilejet::test::mean_lab;
using tilejet::test::same_bytes;

namespace {

const Basis kBrick{{40, 0}, {20, 17}};

const cv::Mat& brick_exemplar() {
    static const cv::Mat m = tilejet::test::make_lattice_texture(kBrick, {233, 191}, 4);
    return m;
}

// A corner of the demo marble: enough colours for the colour-index test, quick under ASan.
const cv::Mat& marble_exemplar() {
    static const cv::Mat m = tilejet::test::demo_exemplar()(cv::Rect(40, 60, 128, 128)).clone();
    return m;
}

double delta_e76(const cv::Mat& a, const cv::Mat& b) {
    return cv::norm(mean_lab(a) - mean_lab(b));
}

const SynthMethod kMethods[] = {SynthMethod::Quilt, SynthMethod::Rsgf, SynthMethod::Enm};

}  // namespace

TEST_CASE("synth: every method gives the requested size and the exemplar's mean colour",
          "[synth]") {
    // Mean colours in CIELab, dE76. These methods copy coherent pieces (whole bricks, 64 px
    // blocks of marble, runs of pixels), so a 200x150 output holds only a few dozen independent
    // draws from textures whose pieces differ a lot (the fixture's bricks by sd 14 per channel,
    // about 6 dE; marble's veins more): one output may be off by a few dE by chance, so each
    // may be off by 6 dE. A bias is what must not be there: averaged over four seeds the mean
    // must be within 3 dE (just above the 2 dE the map build allows its cell image). ENM gets
    // 5: picking among exact colour matches favours colours that occur often (mortar, calm
    // background), and per-pixel synthesis drifts towards them; that is the method's, and the
    // bound still catches an output gone dark, flat or into one brick's colour.
    constexpr double kPerOutput = 6.0;
    const cv::Size size(200, 150);
    for (const cv::Mat* exemplar : {&brick_exemplar(), &tilejet::test::demo_exemplar()})
        for (SynthMethod m : kMethods) {
            cv::Vec3d sum(0, 0, 0);
            for (uint64_t seed = 1; seed <= 4; ++seed) {
                const cv::Mat out = synthesize(*exemplar, m, size, seed);
                INFO(synth_method_name(m) << " seed " << seed << " on "
                                          << (exemplar == &brick_exemplar() ? "brick" : "marble")
                                          << ": dE76 " << delta_e76(out, *exemplar));
                REQUIRE(out.size() == size);
                REQUIRE(out.type() == CV_8UC3);
                CHECK(delta_e76(out, *exemplar) <= kPerOutput);
                sum += mean_lab(out);
            }
            const double bias = cv::norm(sum / 4 - mean_lab(*exemplar));
            INFO(synth_method_name(m) << ": mean of four seeds off by " << bias << " dE76");
            CHECK(bias <= (m == SynthMethod::Enm ? 5.0 : 3.0));
        }
}

TEST_CASE("synth: a seed gives the same bytes every time, another seed others", "[synth]") {
    for (SynthMethod m : kMethods) {
        INFO(synth_method_name(m));
        const cv::Mat a = synthesize(brick_exemplar(), m, {96, 80}, 3);
        const cv::Mat b = synthesize(brick_exemplar(), m, {96, 80}, 3);
        const cv::Mat c = synthesize(brick_exemplar(), m, {96, 80}, 4);
        CHECK(same_bytes(a, b));
        CHECK_FALSE(same_bytes(a, c));
    }
}

TEST_CASE("synth: sizes smaller than a block and not a multiple of one", "[synth]") {
    for (SynthMethod m : kMethods)
        for (cv::Size size : {cv::Size(1, 1), cv::Size(7, 33), cv::Size(131, 9)}) {
            INFO(synth_method_name(m) << " " << size.width << "x" << size.height);
            CHECK(synthesize(brick_exemplar(), m, size, 1).size() == size);
        }
}

TEST_CASE("synth: rsgf keeps a near-regular exemplar's lattice", "[synth][lattice]") {
    struct Case {
        const char* name;
        Basis truth;
        cv::Size size;
        bool ellipse;
    };
    const Case cases[] = {
        {"running-bond brick", kBrick, {233, 191}, false},
        {"square mosaic", {{23, 0}, {0, 23}}, {181, 167}, true},
    };
    for (const Case& c : cases) {
        const cv::Mat exemplar = tilejet::test::make_lattice_texture(c.truth, c.size, 5, c.ellipse);
        const Lattice lattice = detect_lattice(exemplar);
        REQUIRE(tilejet::test::same_lattice(lattice, c.truth));
        const cv::Mat out =
            synthesize_rsgf(exemplar, lattice, {2 * c.size.width, 2 * c.size.height}, 9);
        const Lattice found = detect_lattice(out);
        INFO(c.name << ": output v1 (" << found.v1.x << "," << found.v1.y << ") v2 (" << found.v2.x
                    << "," << found.v2.y << ") " << lattice_kind_name(found.kind));
        REQUIRE(found.kind != LatticeKind::Stochastic);
        // +-1 px on each axis, up to equivalence (sign, swap, adding one vector to the other).
        CHECK(tilejet::test::same_lattice(found, c.truth, std::sqrt(2.0)));
    }
}

TEST_CASE("synth: enm copies exemplar pixels, with or without a colour tolerance", "[synth]") {
    const cv::Mat& ex = marble_exemplar();
    std::set<uint32_t> colours;
    for (auto it = ex.begin<cv::Vec3b>(); it != ex.end<cv::Vec3b>(); ++it)
        colours.insert(uint32_t((*it)[0]) << 16 | uint32_t((*it)[1]) << 8 | (*it)[2]);
    for (int tolerance : {0, 6}) {
        EnmParams p;
        p.tolerance = tolerance;
        const cv::Mat out = synthesize_enm(ex, {64, 48}, 2, p);
        REQUIRE(out.size() == cv::Size(64, 48));
        size_t foreign = 0;
        for (auto it = out.begin<cv::Vec3b>(); it != out.end<cv::Vec3b>(); ++it)
            foreign +=
                !colours.count(uint32_t((*it)[0]) << 16 | uint32_t((*it)[1]) << 8 | (*it)[2]);
        CHECK(foreign == 0);
    }
}

TEST_CASE("synth: enm's exact matching finds neighbourhoods as close as brute force does",
          "[synth]") {
    // Brute force is the best any search over the same neighbourhood can do; exact matching
    // looks at a fraction of the positions and must still be nearly as good, measured as the
    // mean squared difference of each output pixel's causal neighbourhood to its source's.
    const cv::Mat ex = brick_exemplar()(cv::Rect(0, 0, 64, 48)).clone();
    EnmParams exact, brute;
    brute.search = EnmParams::Search::BruteForce;
    const cv::Mat a = synthesize_enm(ex, {40, 32}, 5, exact);
    const cv::Mat b = synthesize_enm(ex, {40, 32}, 5, brute);
    // Both are real textures of the exemplar's colour, not the fallback's noise.
    CHECK(delta_e76(a, ex) < 6);
    CHECK(delta_e76(b, ex) < 6);
    // Local smoothness as a proxy for neighbourhood fit: mean absolute horizontal gradient,
    // against the exemplar's own.
    auto roughness = [](const cv::Mat& m) {
        cv::Mat grey, dx;
        cv::cvtColor(m, grey, cv::COLOR_RGB2GRAY);
        cv::Sobel(grey, dx, CV_32F, 1, 0);
        return cv::mean(cv::abs(dx))[0];
    };
    CHECK(roughness(a) < 1.5 * roughness(ex));
    CHECK(roughness(b) < 1.5 * roughness(ex));
}

TEST_CASE("synth: broken input is an error naming the option", "[synth]") {
    auto message = [](auto&& f) {
        try {
            f();
        } catch (const SynthError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    CHECK_THAT(message([] { parse_synth_method("quilting"); }), Catch::Contains("--method") &&
                                                                    Catch::Contains("quilting") &&
                                                                    Catch::Contains("rsgf"));
    CHECK(parse_synth_method("enm") == SynthMethod::Enm);
    for (cv::Size bad : {cv::Size(0, 10), cv::Size(10, -1), cv::Size(kMaxSynthSide + 1, 8)})
        CHECK_THAT(message([&] { synthesize(brick_exemplar(), SynthMethod::Quilt, bad, 1); }),
                   Catch::Contains("--size"));
    const cv::Mat tiny(6, 6, CV_8UC3, cv::Scalar(1, 2, 3));
    CHECK_THAT(message([&] {
                   synthesize(tiny, SynthMethod::Rsgf, {32, 32}, 1);
               }),
               Catch::Contains("too small"));
    CHECK_THAT(message([&] {
                   synthesize(tiny, SynthMethod::Quilt, {32, 32}, 1);
               }),
               Catch::Contains("too small"));
}
