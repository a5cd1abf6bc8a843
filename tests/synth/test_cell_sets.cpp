// Corner-coloured cell sets (docs/design.md section 9): seamless neighbours whatever the hash
// picks, uniform choice, rendering equal to sampling, old one-image maps unchanged, and no grid.

#include <openssl/evp.h>

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <set>

#include "cell_set.hpp"
#include "fixtures.hpp"
#include "tilejet/colour/statistics.hpp"
#include "tilejet/synth/build.hpp"
#include "tilejet/synth/exemplar.hpp"
#include "tilejet/synth/internal/corner_colours.hpp"
#include "tilejet/synth/internal/lab.hpp"
#include "tilejet/synth/map_file.hpp"
#include "tilejet/synth/quilt.hpp"
#include "tilejet/synth/sampler.hpp"

using namespace tilejet::synth;
using tilejet::test::demo_exemplar;

namespace {

constexpr int kCell = 48;

// A small set of the demo design: K = 2 and two variants, the two plain combinations in four, so
// 36 cell images, 48 px cells.
const TextureMap& small_set() {
    static const TextureMap map = [] {
        BuildParams p;
        p.corner_colours = 2;
        p.variants = 2;  // the default for large cells only: these tests take them small
        p.cell_size = kCell;
        p.patches = 12;
        p.candidates = 96;
        p.seed = 3;
        return build_texture_map(demo_exemplar(), p);
    }();
    return map;
}

cv::Mat lab_of(const cv::Mat& rgb) {
    cv::Mat lab;
    rgb.convertTo(lab, CV_32FC3, 1.0 / 255);
    cv::cvtColor(lab, lab, cv::COLOR_RGB2Lab);
    return lab;
}

// Mean CIE76 difference between column `a` of one image and column `b` of another.
double column_jump(const cv::Mat& lab_a, int a, const cv::Mat& lab_b, int b) {
    double sum = 0;
    for (int y = 0; y < lab_a.rows; ++y)
        sum += cv::norm(lab_a.at<cv::Vec3f>(y, a) - lab_b.at<cv::Vec3f>(y, b));
    return sum / lab_a.rows;
}

// What image `index` of a set is made for: its corners' colours and its variant.
struct Corners {
    int tl, tr, bl, br, variant;
};

Corners corners_of(size_t index, int k) {
    const auto [combination, variant] = tilejet::synth::detail::cell_image_key(uint32_t(k), index);
    const int m = int(combination);
    return {m % k, m / k % k, m / k / k % k, m / k / k / k % k, int(variant)};
}

// Grey grain, side x side px, normal about 110 with deviation 14. Its own generator:
// cv::randn's is the process's, and what other tests drew before would change the grain.
cv::Mat grey_grain(int side, uint64_t seed) {
    cv::Mat grain(side, side, CV_8UC3);
    cv::RNG(seed).fill(grain, cv::RNG::NORMAL, cv::Scalar::all(110), cv::Scalar::all(14));
    return grain;
}

std::string sha256_hex(const cv::Mat& m) {
    std::array<unsigned char, 32> digest{};
    unsigned int len = 0;
    std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(), EVP_MD_CTX_free);
    EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr);
    for (int r = 0; r < m.rows; ++r)
        EVP_DigestUpdate(ctx.get(), m.ptr(r), size_t(m.cols) * m.elemSize());
    EVP_DigestFinal_ex(ctx.get(), digest.data(), &len);
    static const char digits[] = "0123456789abcdef";
    std::string hex;
    for (unsigned char b : digest)
        hex += digits[b >> 4], hex += digits[b & 15];
    return hex;
}

// The periodic-grid detector: how much more a render correlates with itself one or two cells
// away than half a cell off those lags. A plane that repeats its cell image correlates
// strongly at whole cells and nowhere else; a plane without a grid looks the same at both.
double grid_contrast(const cv::Mat& rgb, int cw, int ch) {
    const cv::Mat lab = lab_of(rgb);
    const std::vector<cv::Point> on = {{cw, 0},   {0, ch},     {cw, ch},
                                       {cw, -ch}, {2 * cw, 0}, {0, 2 * ch}};
    double grid = 0, off = 0;
    for (const cv::Point& lag : on) {
        grid += tilejet::test::correlation_at(lab, lag);
        off += tilejet::test::correlation_at(lab, lag + cv::Point(cw / 2, ch / 2));
    }
    return (grid - off) / double(on.size());
}

// How many pixels of `inside` show exactly the same colour in both images.
int pixels_alike(const cv::Mat& a, const cv::Mat& b, const cv::Rect& inside) {
    cv::Mat same;
    cv::compare(a(inside), b(inside), same, cv::CMP_EQ);
    cv::cvtColor(same, same, cv::COLOR_RGB2GRAY);
    return cv::countNonZero(same == 255);
}

// Every pair of images the hash can put side by side or one above the other meets seamlessly:
// the jump across their edge is like a jump between two columns inside an image; pairs the hash
// never picks jump more (the measure can fail).
void require_seamless(const TextureMap& map) {
    REQUIRE((map.variants == 1 || map.variants == 2));
    const bool plain_in_four = map.variant_rule == TextureMap::VariantRule::plain_in_four;
    const int k = map.corner_colours, variants = map.variants;
    // With the parity rule the cells across an edge show the other variant; breaking twins,
    // either variant may stand beside either.
    const bool any_variants = map.variant_rule != TextureMap::VariantRule::parity;
    const int cell = map.cell_images[0].pixels.cols;
    std::vector<cv::Mat> lab, lab_t;  // each image in CIELab, and transposed for vertical pairs
    for (const CellImage& image : map.cell_images) {
        lab.push_back(lab_of(image.pixels));
        lab_t.push_back(lab.back().t());
    }
    // The typical jump between two neighbouring columns or rows inside an image.
    double inside = 0;
    int counted = 0;
    for (size_t m = 0; m < lab.size(); ++m)
        for (int x = 0; x + 1 < cell; ++x, counted += 2)
            inside +=
                column_jump(lab[m], x, lab[m], x + 1) + column_jump(lab_t[m], x, lab_t[m], x + 1);
    inside /= counted;

    double compatible_sum = 0, incompatible_sum = 0;
    int compatible = 0, incompatible = 0;
    for (size_t a = 0; a < lab.size(); ++a)
        for (size_t b = 0; b < lab.size(); ++b) {
            const Corners ca = corners_of(a, k), cb = corners_of(b, k);
            // b right of a, and b below a: the shared corners agree.
            for (const bool beside : {true, false}) {
                const bool fits =
                    (variants == 1 || any_variants || ca.variant != cb.variant) &&
                    (beside ? ca.tr == cb.tl && ca.br == cb.bl : ca.bl == cb.tl && ca.br == cb.tr);
                const double jump = beside ? column_jump(lab[a], cell - 1, lab[b], 0)
                                           : column_jump(lab_t[a], cell - 1, lab_t[b], 0);
                if (fits) {
                    INFO("image " << a << (beside ? " left of " : " above ") << b << ": jump "
                                  << jump << ", inside " << inside);
                    REQUIRE(jump < 2.0 * inside);
                    compatible_sum += jump, ++compatible;
                } else {
                    incompatible_sum += jump, ++incompatible;
                }
            }
        }
    // Every pair the hash can pick: each image has K^2 possible right and K^2 lower neighbours
    // in each variant it may meet, four of a plain one.
    int expected = 0;
    for (size_t a = 0; a < lab.size(); ++a)
        for (const bool beside : {true, false})
            for (int u = 0; u < k; ++u)
                for (int v = 0; v < k; ++v) {
                    const Corners ca = corners_of(a, k);
                    const int tl = beside ? ca.tr : ca.bl, tr = beside ? u : ca.br,
                              bl = beside ? ca.br : u, br = v;
                    const bool plain = tl == tr && tr == bl && bl == br;
                    expected += !any_variants ? 1 : plain && plain_in_four ? 4 : variants;
                }
    REQUIRE(compatible == expected);
    // The measure can fail: pairs the hash never picks do not meet seamlessly.
    INFO("compatible " << compatible_sum / compatible << ", others "
                       << incompatible_sum / incompatible);
    REQUIRE(incompatible_sum / incompatible > 1.5 * compatible_sum / compatible);
}

}  // namespace

TEST_CASE("any two neighbouring cells of a set meet seamlessly, for every pair the hash can pick",
          "[cell_set]") {
    const TextureMap& map = small_set();
    REQUIRE(map.corner_colours == 2);
    REQUIRE(map.variants == 2);
    REQUIRE(map.variant_rule == TextureMap::VariantRule::plain_in_four);
    REQUIRE(map.cell_images.size() == 36);
    require_seamless(map);
}

TEST_CASE("a set from a source shorter than its strips is seamless for every pair the hash picks",
          "[cell_set]") {
    // 64 px cells from a 70 px exemplar: each strip (76 px) is quilted from two blocks, and
    // the cells copy the exemplar itself, not a quilt of it.
    BuildParams p;
    p.corner_colours = 2;  // a source this small gets four by default: 520 images to check
    p.cell_size = 64;
    p.patches = 4;
    p.candidates = 8;
    cv::Mat exemplar;
    demo_exemplar()(cv::Rect(60, 50, 70, 70)).copyTo(exemplar);
    const TextureMap map = build_texture_map(exemplar, p);
    REQUIRE(map.source.size() == exemplar.size());
    REQUIRE(map.cell_images.size() == 36);
    require_seamless(map);
}

TEST_CASE(
    "cuts through an enlarged exemplar are blended as soft as the stone, cells still seamless",
    "[cell_set]") {
    // The demo design's middle enlarged 4 times (as for 200 dpi from a 50 dpi scan): nothing in
    // it changes faster than over a few pixels, and a hard one-pixel cut would stand out.
    cv::Mat enlarged;
    cv::resize(demo_exemplar()(cv::Rect(96, 96, 72, 72)), enlarged, {288, 288}, 0, 0,
               cv::INTER_CUBIC);
    auto build = [&](double dpi, double exemplar_dpi) {
        BuildParams p;
        p.corner_colours = 2;
        p.variants = 1;
        p.cell_size = 96;
        p.patches = 12;
        p.candidates = 96;
        p.seed = 5;
        p.dpi = dpi, p.exemplar_dpi = exemplar_dpi;
        return build_texture_map(enlarged, p);
    };
    const TextureMap hard = build(0, 0), soft = build(200, 50);
    require_seamless(soft);

    // Hard edges: steps between neighbouring pixels larger than any but the top 0.1 % of the
    // enlarged exemplar's own.
    auto steps = [](const cv::Mat& rgb) {
        const cv::Mat lab = lab_of(rgb);
        std::vector<double> out;
        for (int y = 0; y + 1 < lab.rows; ++y)
            for (int x = 0; x + 1 < lab.cols; ++x) {
                const cv::Vec3f p = lab.at<cv::Vec3f>(y, x);
                out.push_back(cv::norm(p - lab.at<cv::Vec3f>(y, x + 1)));
                out.push_back(cv::norm(p - lab.at<cv::Vec3f>(y + 1, x)));
            }
        return out;
    };
    std::vector<double> own = steps(enlarged);
    const double sharpest = tilejet::colour::percentile(own, 0.999);
    auto hard_share = [&](const TextureMap& map) {
        size_t above = 0, all = 0;
        for (const CellImage& image : map.cell_images)
            for (double step : steps(image.pixels))
                above += step > sharpest, ++all;
        return double(above) / double(all);
    };
    const double hard_edges = hard_share(hard), soft_edges = hard_share(soft);
    INFO("share of steps above the exemplar's 99.9th percentile ("
         << sharpest << " dE): cuts " << hard_edges << ", blended " << soft_edges);
    REQUIRE(hard_edges > 0.004);  // the measure can fail: hard cuts show in it
    // Cuts round the corner cores blend too (into the core's own surroundings): with those
    // cuts left hard the blended set kept 0.21 of the hard share, with them blended 0.13.
    REQUIRE(soft_edges < 0.17 * hard_edges);
    REQUIRE(soft_edges < 0.0016);
}

TEST_CASE("what a cell shows along an edge depends only on the edge's corner colours",
          "[cell_set]") {
    const TextureMap& map = small_set();
    const int k = map.corner_colours;
    // The frame: some columns along the right edge are the same in all images with the same
    // right corners (and likewise for the other edges), so neighbours always share them.
    std::map<std::pair<int, int>, cv::Mat> right, bottom;
    for (size_t m = 0; m < map.cell_images.size(); ++m) {
        const Corners c = corners_of(m, k);
        const cv::Mat col = map.cell_images[m].pixels.col(kCell - 1);
        const cv::Mat row = map.cell_images[m].pixels.row(kCell - 1);
        auto [r, fresh_r] = right.emplace(std::pair{c.tr, c.br}, col);
        auto [b, fresh_b] = bottom.emplace(std::pair{c.bl, c.br}, row);
        if (!fresh_r) REQUIRE(cv::norm(r->second, col, cv::NORM_INF) == 0);
        if (!fresh_b) REQUIRE(cv::norm(b->second, row, cv::NORM_INF) == 0);
    }
    REQUIRE(right.size() == size_t(k * k));
    // And images differ elsewhere: they are not one image repeated.
    REQUIRE(cv::norm(map.cell_images[0].pixels, map.cell_images[15].pixels, cv::NORM_INF) > 0);
}

TEST_CASE("the cell image of a cell is uniform over the set (chi-square)", "[cell_set]") {
    // Only the map id and K decide; no images are needed to count.
    TextureMap map;
    map.corner_colours = 3;
    map.id[0] = 0x5a, map.id[5] = 0x17;
    const int images = 81;
    std::vector<double> count(images, 0);
    std::vector<double> next(9, 0);  // the right neighbour's new corners, given this cell's
    const int side = 300;
    for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) {
            const uint32_t m = cell_image_index(map, 99, {i - 150, j + 7000});
            REQUIRE(m < uint32_t(images));
            ++count[m];
            const uint32_t r = cell_image_index(map, 99, {i - 149, j + 7000});
            // Seamless: the right neighbour's left corners are this cell's right corners.
            REQUIRE(r % 3 == m / 3 % 3);
            REQUIRE(r / 9 % 3 == m / 27);
            ++next[(r / 3 % 3) + 3 * (r / 27)];
        }
    auto chi_square = [](const std::vector<double>& observed) {
        double total = 0, chi = 0;
        for (double o : observed)
            total += o;
        const double expected = total / double(observed.size());
        for (double o : observed)
            chi += (o - expected) * (o - expected) / expected;
        return chi;
    };
    // Critical values at p = 0.001: 124.8 for 80 degrees of freedom, 26.1 for 8.
    CHECK(chi_square(count) < 124.8);
    CHECK(chi_square(next) < 26.1);
    // With two variants by parity, each is uniform over its parity's cells and the corners as
    // before.
    map.corner_colours = 2, map.variants = 2, map.variant_rule = TextureMap::VariantRule::parity;
    std::vector<double> even(16, 0), odd(16, 0);
    for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) {
            const uint32_t m = cell_image_index(map, 99, {i - 150, j + 7000});
            REQUIRE(m < 32);
            REQUIRE(m / 16 == uint32_t((i + j) % 2));
            ++((i + j) % 2 ? odd : even)[m % 16];
        }
    // 15 degrees of freedom.
    CHECK(chi_square(even) < 37.7);
    CHECK(chi_square(odd) < 37.7);
    // Breaking twins, the combination stays uniform; the second variant goes where it breaks
    // one, about one cell in five.
    map.variant_rule = TextureMap::VariantRule::break_twins;
    std::vector<double> combinations(16, 0);
    double second = 0;
    for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) {
            const uint32_t m = cell_image_index(map, 99, {i - 150, j + 7000});
            REQUIRE(m < 32);
            ++combinations[m % 16];
            second += m / 16;
        }
    CHECK(chi_square(combinations) < 37.7);
    INFO("cells showing the second variant: " << second / (side * side));
    CHECK(second > 0.1 * side * side);
    CHECK(second < 0.35 * side * side);
    // Hashed, every image of the set shows about equally often, twins broken or not.
    map.variant_rule = TextureMap::VariantRule::hashed;
    std::vector<double> shown(32, 0);
    for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) {
            const uint32_t m = cell_image_index(map, 99, {i - 150, j + 7000});
            REQUIRE(m < 32);
            ++shown[m];
        }
    // 31 degrees of freedom.
    CHECK(chi_square(shown) < 61.1);
    // Plain cells in four: each combination shows as often as before, each of its variants
    // equally often (a plain one's four, each other's two).
    map.variant_rule = TextureMap::VariantRule::plain_in_four;
    std::vector<double> plain(8, 0), other(32, 0);
    for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) {
            const uint32_t m = cell_image_index(map, 99, {i - 150, j + 7000});
            REQUIRE(m < 36);
            // Images 0 and 15 (all corners 0, all 1) and 32 to 35 are plain, 16 and 31 too.
            const uint32_t combination = m < 32 ? m % 16 : (m - 32) / 2 * 15;
            const bool is_plain = combination == 0 || combination == 15;
            if (!is_plain) {
                ++other[m];
                continue;
            }
            const uint32_t variant = m < 32 ? m / 16 : 2 + (m - 32) % 2;
            ++plain[(combination == 15 ? 4 : 0) + variant];
        }
    std::erase_if(other, [](double o) { return o == 0; });
    REQUIRE(other.size() == 28);
    // 27 and 7 degrees of freedom; the plain images each show half as often as the others.
    CHECK(chi_square(other) < 55.5);
    CHECK(chi_square(plain) < 24.3);
    const double per_plain = std::accumulate(plain.begin(), plain.end(), 0.0) / 8;
    const double per_other = std::accumulate(other.begin(), other.end(), 0.0) / 28;
    CHECK(per_plain / per_other == Approx(0.5).epsilon(0.1));
    map.corner_colours = 3, map.variants = 1;
    // Another seed picks differently.
    const bool differs = cell_image_index(map, 100, {0, 0}) != cell_image_index(map, 99, {0, 0}) ||
                         cell_image_index(map, 100, {1, 0}) != cell_image_index(map, 99, {1, 0}) ||
                         cell_image_index(map, 100, {2, 0}) != cell_image_index(map, 99, {2, 0});
    REQUIRE(differs);
}

TEST_CASE("variants keep a cell's eight neighbours from showing its image", "[cell_set]") {
    // With one image per combination of K = 2 corner colours, two neighbours show the same
    // image when the three vertices along each side of the pair agree (across an edge), or the
    // three along the diagonal and the two pairs beside it (across a vertex): one pair in 16
    // either way, a motif doubled side by side.
    TextureMap map;
    map.corner_colours = 2;
    map.id[3] = 0x41;
    struct Twins {
        int edge = 0, vertex = 0;
    };
    auto twins = [&map] {
        Twins t;
        for (int64_t j = -100; j < 100; ++j)
            for (int64_t i = -100; i < 100; ++i) {
                const uint32_t m = cell_image_index(map, 5, {i, j});
                t.edge += m == cell_image_index(map, 5, {i + 1, j});
                t.edge += m == cell_image_index(map, 5, {i, j + 1});
                t.vertex += m == cell_image_index(map, 5, {i + 1, j + 1});
                t.vertex += m == cell_image_index(map, 5, {i - 1, j + 1});
            }
        return t;
    };
    map.variants = 1;
    const Twins one = twins();
    map.variants = 2, map.variant_rule = TextureMap::VariantRule::parity;
    const Twins parity = twins();
    map.variant_rule = TextureMap::VariantRule::break_twins;
    const Twins broken = twins();
    map.variant_rule = TextureMap::VariantRule::hashed;
    const Twins hashed = twins();
    map.variant_rule = TextureMap::VariantRule::plain_in_four;
    const Twins in_four = twins();
    INFO("pairs showing one image, of 80000 across an edge / 80000 across a vertex: one variant "
         << one.edge << " / " << one.vertex << ", by parity " << parity.edge << " / "
         << parity.vertex << ", breaking twins " << broken.edge << " / " << broken.vertex);
    CHECK(one.edge > 80000 / 16 * 8 / 10);
    CHECK(one.vertex > 80000 / 16 * 8 / 10);
    CHECK(parity.edge == 0);
    CHECK(parity.vertex > 80000 / 16 * 8 / 10);
    CHECK(broken.edge == 0);
    CHECK(broken.vertex < one.vertex / 3);
    // Hashed, cells without a twin pick either variant: twins are parted as before, and two
    // cells of different combinations never show one image anyway.
    INFO("hashed " << hashed.edge << " / " << hashed.vertex);
    CHECK(hashed.edge == 0);
    CHECK(hashed.vertex < one.vertex / 3);
    // Those left were plain cells round a vertex of 3 x 3 alike (texture_map.hpp): with their
    // four variants no cell shows its image across an edge or a vertex.
    INFO("plain cells in four " << in_four.edge << " / " << in_four.vertex);
    CHECK(hashed.vertex > 0);
    CHECK(in_four.edge == 0);
    CHECK(in_four.vertex == 0);
}

TEST_CASE("by default a set has two variants whatever the grain, one only for slabs of 3 colours",
          "[cell_set][slab][heavy]") {
    // Fine grain kept one until its twins across a vertex, whole cell images, drew granite's
    // and terrazzo's periodicity to 3.6 (build.hpp).
    const cv::Mat fine = grey_grain(420, 7);
    cv::Mat coarse;
    cv::GaussianBlur(fine, coarse, {0, 0}, 6);
    BuildParams p;
    p.patches = 2;
    p.candidates = 2;
    // Two corner colours, the counts below those of 16 combinations (256 px cells get three by
    // default since session 39).
    p.corner_colours = 2;
    // Cells from the grain (256 px here).
    const TextureMap of_fine = build_texture_map(fine, p), of_coarse = build_texture_map(coarse, p);
    INFO("grain: fine " << of_fine.build.grain << " px, coarse " << of_coarse.build.grain << " px");
    REQUIRE(of_fine.build.grain > 0);
    REQUIRE(of_fine.build.grain < of_coarse.build.grain);
    CHECK(of_fine.variants == 2);
    CHECK(of_fine.cell_images.size() == 36);
    CHECK(of_fine.variant_rule == TextureMap::VariantRule::plain_in_four);
    CHECK(of_coarse.variants == 2);
    CHECK(of_coarse.cell_images.size() == 36);
    CHECK(of_coarse.variant_rule == TextureMap::VariantRule::plain_in_four);
    // Cells over kLargeCell (320 px) that copy their source more than once get two whatever
    // the grain; so do cells given by --cell, whose grain is not measured.
    p.cell_size = 336;
    CHECK(build_texture_map(fine, p).variants == 2);
    p.cell_size = 320;
    CHECK(build_texture_map(fine, p).variants == 2);
    // Cells over kLargeCell from a source their 16 images cover less than once get two as
    // well: with two colours one variant leaves a twin across one edge in 16 (a 4096 px slab
    // showed its white blob in cells one above the other). Only sets of three colours or more
    // keep one there (an 8192 px slab lost the stone's contrast with two).
    p.cell_size = 336;
    const TextureMap slab = build_texture_map(grey_grain(1400, 9), p);
    CHECK(slab.corner_colours == 2);
    CHECK(slab.variants == 2);
    CHECK(slab.cell_images.size() == 36);
}

TEST_CASE(
    "sets of three colours or more keep one variant only for large cells copied less than once",
    "[cell_set][slab]") {
    // The rule alone (CellSet::default_variants), without the minutes a set of 81 images of
    // over 320 px takes to build: one variant where K^4 cells of the size copy less than the
    // source, over kLargeCell (320 px), with three colours or more.
    using tilejet::synth::detail::CellSet;
    // Cells up to 320 px: two, whatever the source.
    CHECK(CellSet::default_variants(3, {320, 320}, {8192, 8192}) == 2);
    CHECK(CellSet::default_variants(3, {256, 256}, {384, 384}) == 2);
    // Two colours: two, whatever the cell and the source (the 4096 px slab's twins, session 40).
    CHECK(CellSet::default_variants(2, {640, 640}, {4096, 4096}) == 2);
    CHECK(CellSet::default_variants(2, {640, 640}, {8192, 8192}) == 2);
    // Three colours of 640 px: 81 x 640^2 px is the source of 5760^2; from it on, copied less
    // than once, one variant (an 8192 px slab lost the stone's contrast with two).
    CHECK(CellSet::default_variants(3, {640, 640}, {1843, 1843}) == 2);
    CHECK(CellSet::default_variants(3, {640, 640}, {5760, 5760}) == 2);
    CHECK(CellSet::default_variants(3, {640, 640}, {5761, 5761}) == 1);
    CHECK(CellSet::default_variants(3, {640, 640}, {8192, 8192}) == 1);
    CHECK(CellSet::default_variants(3, {640, 320}, {8192, 8192}) == 2);  // its shorter side
    // Four colours: 256 images of 640 px copy an 8192 px source more than once.
    CHECK(CellSet::default_variants(4, {640, 640}, {8192, 8192}) == 2);
    CHECK(CellSet::default_variants(4, {640, 640}, {10241, 10241}) == 1);
    // Four colours of cells up to 320 px (the corpus's designs): one, 256 images, where a twin
    // shows one time in 256; but two (520 images) from sources under 256 px (pattern files).
    CHECK(CellSet::default_variants(4, {256, 256}, {384, 384}) == 1);
    CHECK(CellSet::default_variants(4, {320, 320}, {256, 256}) == 1);
    CHECK(CellSet::default_variants(4, {64, 64}, {255, 255}) == 2);
    CHECK(CellSet::default_variants(4, {64, 64}, {100, 100}) == 2);
}

TEST_CASE(
    "four-colour sets of cells up to 320 px have strips an eighth of the cell, where the "
    "source holds them",
    "[cell_set]") {
    using tilejet::synth::detail::CellSet;
    // An eighth with four colours, where the source (256 px or more) holds an inside block
    // (three quarters of the cell) and the frame; else a tenth.
    CHECK(CellSet::frame_for(4, {256, 256}, {384, 384}, false) == 32);
    CHECK(CellSet::frame_for(3, {256, 256}, {384, 384}, false) == 25);
    CHECK(CellSet::frame_for(4, {256, 256}, {384, 384}, true) == 25);       // a lattice
    CHECK(CellSet::frame_for(4, {256, 256}, {256, 256}, false) == 25);      // 192 + 64 + 2 > 256
    CHECK(CellSet::frame_for(4, {200, 200}, {256, 256}, false) == 25);      // 150 + 50 + 2 <= 256
    CHECK(CellSet::frame_for(4, {64, 64}, {100, 100}, false) == 6);         // a pattern file
    CHECK(CellSet::frame_for(4, {640, 640}, {10241, 10241}, false) == 64);  // large cells
}

TEST_CASE("the two variants of a small source's set differ, the first as one variant builds it",
          "[cell_set]") {
    // A source no larger than a block search's window is searched whole: a second variant with
    // an account of its own (as large cells' have) repeated the first's images pixel for pixel,
    // and cells side by side showed one image, as with one variant.
    const cv::Mat noise = grey_grain(160, 7);
    BuildParams p;
    p.corner_colours = 2;  // the counts below; a source this small gets three by default
    p.patches = 2;
    p.candidates = 2;
    p.cell_size = 40;
    p.variants = 2;
    const TextureMap two = build_texture_map(noise, p);
    CHECK(two.variants == 2);
    CHECK(two.cell_images.size() == 36);
    p.variants = 1;
    const TextureMap one = build_texture_map(noise, p);
    CHECK(one.variants == 1);
    CHECK(one.cell_images.size() == 16);
    // The first variant's images are what a one-variant build makes: the second is made after.
    for (size_t i = 0; i < 16; ++i)
        CHECK(cv::norm(two.cell_images[i].pixels, one.cell_images[i].pixels, cv::NORM_INF) == 0);
    // The second differs from the first inside the frame they share.
    const int frame = 40 / 10 + 1;
    const cv::Rect inside(frame, frame, 40 - 2 * frame, 40 - 2 * frame);
    for (size_t i = 0; i < 16; ++i) {
        const int alike =
            pixels_alike(two.cell_images[i].pixels, two.cell_images[i + 16].pixels, inside);
        INFO("combination " << i << ": pixels alike in both variants " << alike << " of "
                            << inside.area());
        CHECK(alike < inside.area() / 2);
    }
}

TEST_CASE("a set renders region by region exactly as Sampler::sample", "[cell_set][sampler]") {
    const TextureMap& map = small_set();
    const int64_t big = int64_t(1) << 31;
    for (const Region region : {Region{-333, 71, 437, 291}, Region{big - 300, -big, 300, 200}}) {
        const cv::Mat out = render_region(map, 77, region, 2);
        // Several cell images show in it.
        std::set<uint32_t> seen;
        for (int64_t j = region.y / kCell - 1; j <= (region.y + region.height) / kCell; ++j)
            for (int64_t i = region.x / kCell - 1; i <= (region.x + region.width) / kCell; ++i)
                seen.insert(cell_image_index(map, 77, {i, j}));
        REQUIRE(seen.size() >= 8);
        INFO("region at " << region.x << "," << region.y);
        REQUIRE(tilejet::test::pixels_unlike_sampler(map, 77, region, out) == 0);
    }
}

TEST_CASE("a set shows no patches unless they are asked for", "[cell_set][sampler]") {
    BuildParams p;
    p.corner_colours = 2;
    p.variants = 2;
    p.cell_size = kCell;
    p.seed = 3;
    const TextureMap bare = build_texture_map(demo_exemplar(), p);
    REQUIRE(bare.cell_images.size() == 36);
    for (const CellImage& image : bare.cell_images) {
        CHECK(image.a.patches.empty());
        CHECK(image.b.patches.empty());
    }
    // Through the file and back it renders as it samples, every pixel its cell image's own.
    const TextureMap again = decode_texture_map(encode_texture_map(bare), "bare.tjmap");
    const Region region{-333, 71, 437, 291};
    const cv::Mat out = render_region(again, 77, region, 2);
    REQUIRE(tilejet::test::pixels_unlike_sampler(again, 77, region, out) == 0);
    const auto floor_div = [](int64_t a, int64_t b) {
        return a >= 0 ? a / b : -((-a + b - 1) / b);
    };
    size_t unlike_image = 0;
    for (int y = 0; y < out.rows; ++y)
        for (int x = 0; x < out.cols; ++x) {
            const int64_t px = region.x + x, py = region.y + y;
            const int64_t i = floor_div(px, kCell), j = floor_div(py, kCell);
            const cv::Mat& image = again.cell_images[cell_image_index(again, 77, {i, j})].pixels;
            unlike_image += out.at<cv::Vec3b>(y, x) !=
                            image.at<cv::Vec3b>(int(py - j * kCell), int(px - i * kCell));
        }
    CHECK(unlike_image == 0);
    // Asked for, they are made from the same images.
    p.active_per_cell = 4;
    const TextureMap patched = build_texture_map(demo_exemplar(), p);
    REQUIRE(patched.cell_images.size() == bare.cell_images.size());
    size_t patches = 0;
    for (size_t m = 0; m < patched.cell_images.size(); ++m) {
        const CellImage& image = patched.cell_images[m];
        patches += image.a.patches.size() + image.b.patches.size();
        CHECK(cv::norm(image.pixels, bare.cell_images[m].pixels, cv::NORM_INF) == 0);
    }
    CHECK(patches > 0);
}

TEST_CASE("a map of one cell image from before cell sets loads and renders as it did",
          "[cell_set][map_file]") {
    // Made by the tilejet of commit a473b0c (map build config/demo/green-marble.png --cell 32
    // --patches 80 --seed 3), with the SHA-256 of its renders from that tilejet's `render
    // --threads 1 -o X.raw`.
    const TextureMap map = load_texture_map(std::filesystem::path(TILEJET_SOURCE_DIR) /
                                            "tests/synth/data/legacy-one-cell-image.tjmap");
    REQUIRE(map.cell_images.size() == 1);
    REQUIRE(map.corner_colours == 1);
    REQUIRE(map.id_hex().substr(0, 16) == "c13f996e9378fb88");
    CHECK(sha256_hex(render_region(map, 7, {0, 0, 300, 200}, 1)) ==
          "47fc8958c39417cfc0bd65ca899f64b920afc184be07bfdee95041b907cc49e4");
    CHECK(sha256_hex(render_region(map, 41237, {-1000000, 77777, 257, 131}, 2)) ==
          "c1249fe1d9f512328f9c32da85ba93bc665550fd5473ee908ba9ed62605f0bfa");
    // Saved again, it keeps its id: no CSET section is added to a one-image map.
    REQUIRE(decode_texture_map(encode_texture_map(map), "again").id == map.id);
}

TEST_CASE("a set of two variants by parity from before twins were broken renders as it did",
          "[cell_set][map_file]") {
    // Made by the tilejet of commit 2b4166d (map build config/demo/green-marble.png --dpi 50
    // --cell 32 --patches 12 --variants 2 --seed 3), with the SHA-256 of its renders from that
    // tilejet's `render -o X.raw`: a job re-rendered months later prints the same tiles.
    const auto path = std::filesystem::path(TILEJET_SOURCE_DIR) /
                      "tests/synth/data/legacy-two-variants-by-parity.tjmap";
    const TextureMap map = load_texture_map(path);
    REQUIRE(map.variants == 2);
    REQUIRE(map.variant_rule == TextureMap::VariantRule::parity);
    REQUIRE(format_version_of(map) == 2);
    REQUIRE(map.id_hex().substr(0, 16) == "0cb43884f1f8e210");
    CHECK(sha256_hex(render_region(map, 7, {0, 0, 300, 200}, 1)) ==
          "36b9b4981fb1cb41be48740bef5a7aea40daaddfc856821a5b5f64861bbbae09");
    CHECK(sha256_hex(render_region(map, 41237, {-1000000, 77777, 257, 131}, 2)) ==
          "6266a4aadd302806ef791f289a5dada27619b3644307c1748b6fe9db9d0b19de");
    // Saved again it is version 2 with its id: no rule is added to its CSET.
    const std::vector<uint8_t> bytes = encode_texture_map(map);
    REQUIRE(bytes[8] == 2);
    REQUIRE(decode_texture_map(bytes, "again").id == map.id);
}

TEST_CASE("the grid detector sees the grid of a one-image map and none in a cell set",
          "[cell_set][quality][heavy]") {
    // The one-image map of the demo design as tilejet made it before cell sets (32 px cells),
    // against a set of the same design and cell size built now.
    const TextureMap old_map = load_texture_map(std::filesystem::path(TILEJET_SOURCE_DIR) /
                                                "tests/synth/data/legacy-one-cell-image.tjmap");
    BuildParams p;
    p.cell_size = 32;
    p.patches = 12;
    p.candidates = 96;
    p.seed = 3;
    p.corner_colours = 2;  // the fewest a set has: its grid is the one to look for
    const TextureMap set = build_texture_map(demo_exemplar(), p);
    REQUIRE(set.cell_images.size() == 36);  // 2 corner colours, two variants
    const Region region{1000, -2000, 384, 384};
    const double old_grid = grid_contrast(render_region(old_map, 7, region), 32, 32);
    const double new_grid = grid_contrast(render_region(set, 7, region), 32, 32);
    // The zero point: image quilting of the exemplar has no grid at all.
    const double quilted =
        grid_contrast(quilt_texture(demo_exemplar(), {384, 384}, 5, 32).rgb, 32, 32);
    INFO("grid contrast: one image " << old_grid << ", cell set " << new_grid << ", quilt "
                                     << quilted);
    // Quilting's block choices follow its FFT match costs, whose last bits differ between CPUs
    // (OpenCV dispatches its DFT kernels by instruction set): 0.07 on an AMD EPYC, under 0.05
    // where this was first measured. Either is far from a grid.
    CHECK(std::abs(quilted) < 0.1);
    CHECK(old_grid > 0.5);
    // What is left is the thin frames that neighbours share (a quarter block wide).
    CHECK(new_grid < 0.15);
}

TEST_CASE("a set's variants survive saving, and a count that does not fit is refused on load",
          "[cell_set][map_file]") {
    TextureMap map = small_set();
    // Built, a set is stored coded against its source (version 4, test_cell_image_coding.cpp);
    // stored as pixels it has the version its rule came with.
    REQUIRE(encode_texture_map(map)[8] == 4);
    map.cell_storage = TextureMap::CellStorage::pixels;
    {
        const std::vector<uint8_t> bytes = encode_texture_map(map);
        const TextureMap again = decode_texture_map(bytes, "again");
        REQUIRE(again.variants == 2);
        REQUIRE(again.variant_rule == TextureMap::VariantRule::plain_in_four);
        REQUIRE(again.id == map.id);
        REQUIRE(bytes[8] == 3);  // the format version the rule came with
        // A version 2 reader would take it for a parity map and render other tiles: a file
        // that claims version 2 with a rule is refused.
        std::vector<uint8_t> claimed_2 = bytes;
        claimed_2[8] = 2;
        CHECK_THROWS_WITH(decode_texture_map(claimed_2, "crafted.tjmap"),
                          Catch::Contains("crafted.tjmap") &&
                              Catch::Contains("variant rule 3 in a map of format version 2"));
        // The rule is content: the same images by parity are another map, of version 2.
        TextureMap by_parity = map;
        by_parity.variant_rule = TextureMap::VariantRule::parity;
        by_parity.cell_images.resize(32);  // no plain combination in four
        assign_map_id(by_parity);
        REQUIRE(by_parity.id != map.id);
        const std::vector<uint8_t> parity_bytes = encode_texture_map(by_parity);
        REQUIRE(parity_bytes[8] == 2);
        REQUIRE(decode_texture_map(parity_bytes, "parity").variant_rule ==
                TextureMap::VariantRule::parity);
    }
    {
        TextureMap unknown = map;
        unknown.variant_rule = TextureMap::VariantRule(7);
        assign_map_id(unknown);
        CHECK_THROWS_WITH(decode_texture_map(encode_texture_map(unknown), "crafted.tjmap"),
                          Catch::Contains("crafted.tjmap") && Catch::Contains("CSET") &&
                              Catch::Contains("variant rule 7 is unknown"));
    }
    {
        TextureMap without_plain_four = map;  // 36 images held, 32 expected
        without_plain_four.variant_rule = TextureMap::VariantRule::hashed;
        assign_map_id(without_plain_four);
        CHECK_THROWS_WITH(
            decode_texture_map(encode_texture_map(without_plain_four), "crafted.tjmap"),
            Catch::Contains("crafted.tjmap") && Catch::Contains("CSET") &&
                Catch::Contains("need 32 cell images, the map holds 36"));
    }
    map.variant_rule = TextureMap::VariantRule::hashed;
    map.cell_images.resize(32);
    map.variants = 1;  // 16 images expected, 32 held
    assign_map_id(map);
    CHECK_THROWS_WITH(decode_texture_map(encode_texture_map(map), "crafted.tjmap"),
                      Catch::Contains("crafted.tjmap") && Catch::Contains("CSET") &&
                          Catch::Contains("need 16 cell images, the map holds 32"));
    map.variants = 3;
    assign_map_id(map);
    CHECK_THROWS_WITH(
        decode_texture_map(encode_texture_map(map), "crafted.tjmap"),
        Catch::Contains("crafted.tjmap") && Catch::Contains("variants 3 is out of range"));
}

TEST_CASE("a set whose patch reaches over its cell's edge is refused on load",
          "[cell_set][map_file]") {
    TextureMap map = small_set();
    // The patch of image 0 nearest the cell's middle row, moved to start one pixel left of
    // the cell: still in the cell's diamond, but over the neighbour's image.
    Patch* moved = nullptr;
    for (Patch& p : map.cell_images[0].a.patches)
        if (!moved || std::abs(p.y + p.height / 2 - kCell / 2) <
                          std::abs(moved->y + moved->height / 2 - kCell / 2))
            moved = &p;
    REQUIRE(moved);
    int left = INT32_MAX;
    for (const MaskRun& run : moved->runs)
        left = std::min(left, moved->x + run.x);
    moved->x -= left + 1;
    assign_map_id(map);
    CHECK_THROWS_WITH(
        decode_texture_map(encode_texture_map(map), "crafted.tjmap"),
        Catch::Contains("crafted.tjmap") && Catch::Contains("of a cell set leaves its cell"));
}

TEST_CASE("a source's one conspicuous feature shows in two cell images at most and in no strip",
          "[cell_set][slab][heavy]") {
    // Calm grey grain with one white disc: what a set copies of the disc recurs wherever its
    // cell image or strip does, at the same place of one cell in 16 (a strip's: a quarter of
    // all edges, K = 2). Large cells only (cell_set.cpp, kLargeCell): the 320 px and smaller
    // cells of exemplars under 1024 px are made as before. Made with no cost on conspicuous
    // pixels, this set showed the disc in 4 images; charged for every copy but an image's
    // first, in 1 or 2 (a block's cut may leave a piece of it to the next). Strips pay for their
    // first copy too: none holds any of it. (Until session 36 images paid for their first copy
    // as well and none showed the disc: the demo design lost its white veins that way.)
    const int cell = 336, side = 840;
    cv::Mat noise = grey_grain(side, 5);
    cv::GaussianBlur(noise, noise, {0, 0}, 1.5);
    cv::circle(noise, {side / 2, side / 2}, 52, cv::Scalar::all(250), cv::FILLED, cv::LINE_AA);
    BuildParams p;
    p.corner_colours = 2;
    p.variants = 1;  // the disc's budget is the set's 16 images, as when this test was written
    p.cell_size = cell;
    p.patches = 4;
    p.candidates = 16;
    p.seed = 5;
    const TextureMap map = build_texture_map(noise, p);
    REQUIRE(map.cell_images.size() == 16);

    // A strip shows in the frames of several images (K = 2: each at the top of four and the
    // bottom of four), so the disc in a strip whites the frames of several; an image's own
    // block may reach into the inner part of its frame (how deep a cell keeps its strips
    // wanders, cell_layout.hpp), and that shows in that image only.
    const int frame = cell / 10;  // cell_set.cpp: the frame is a tenth of the cell
    int images_with_disc = 0, frames_with_disc = 0, frame_pixels = 0;
    for (const CellImage& image : map.cell_images) {
        cv::Mat white;
        cv::inRange(image.pixels, cv::Scalar::all(200), cv::Scalar::all(255), white);
        images_with_disc += cv::countNonZero(white) >= 100;
        cv::Mat inner = white.clone();
        inner(cv::Rect(frame, frame, cell - 2 * frame, cell - 2 * frame)).setTo(0);
        frame_pixels += cv::countNonZero(inner);
        frames_with_disc += cv::countNonZero(inner) > 0;
    }
    INFO("images showing the disc: " << images_with_disc << ", frames showing it "
                                     << frames_with_disc << " (" << frame_pixels << " px)");
    CHECK(frames_with_disc <= 1);
    CHECK(images_with_disc <= 2);
}

TEST_CASE("the corner cores of a small-celled set hold no fleck", "[cell_set][heavy]") {
    // Grey grain strewn with white flecks, a tenth of the surface: half of all random cores
    // would hold one. A core shows whole at every vertex of its colour (half of them, K = 2),
    // and marble's one white fleck in a core drew a grid of dots (map seed 4). The four
    // corners of every cell image are quarters of cores.
    const int side = 256, cell = 96;
    const int core = std::max(2, std::max(3, cell / 10) / 3);  // cell_set.cpp: c = w / 3
    cv::Mat source(side, side, CV_8UC3);
    cv::RNG rng(11);
    rng.fill(source, cv::RNG::NORMAL, cv::Scalar::all(100), cv::Scalar::all(6));
    for (int i = 0; i < side * side / 90; ++i) {
        const cv::Point at(rng.uniform(0, side - 3), rng.uniform(0, side - 3));
        source(cv::Rect(at, cv::Size(3, 3))).setTo(cv::Scalar::all(250));
    }
    cv::Mat white;
    cv::inRange(source, cv::Scalar::all(200), cv::Scalar::all(255), white);
    INFO("white share of the source " << cv::countNonZero(white) / double(side * side));
    BuildParams p;
    p.cell_size = cell;
    p.corner_colours = 2;  // a core at half the vertices: where a fleck shows most
    p.variants = 1;
    p.patches = 2;
    p.candidates = 2;
    p.lattice = BuildParams::Lattice::Off;
    int corners_with_fleck = 0, corners = 0;
    for (const uint64_t seed : {1, 2, 3, 4}) {
        p.seed = seed;
        const TextureMap map = build_texture_map(source, p);
        REQUIRE(map.corner_colours == 2);
        for (const CellImage& image : map.cell_images)
            for (const cv::Point at :
                 {cv::Point(0, 0), cv::Point(cell - core, 0), cv::Point(0, cell - core),
                  cv::Point(cell - core, cell - core)}) {
                cv::Mat fleck;
                cv::inRange(image.pixels(cv::Rect(at, cv::Size(core, core))), cv::Scalar::all(200),
                            cv::Scalar::all(255), fleck);
                corners_with_fleck += cv::countNonZero(fleck) > 0;
                ++corners;
            }
    }
    INFO("cell image corners showing a fleck: " << corners_with_fleck << " of " << corners);
    CHECK(corners_with_fleck == 0);
}

TEST_CASE("every block of a set's images is matched to what it joins, even from a small source",
          "[cell_set]") {
    // 32 images of 160 px cells from the 256 px demo design: each image quilts four blocks of
    // about 95 px at the same four places, from 162 x 162 possible windows. Windows that would
    // show an earlier image's copy again at the same place used to be banned outright, each ban
    // a third of all windows: from the fourth image or so no window was left, and the block went
    // in at random, its seams wherever the cut found least bad (corpus designs: three blocks in
    // five). Now such windows cost more instead.
    using tilejet::synth::detail::CellSet;
    using tilejet::synth::detail::CellSetParams;
    const cv::Mat& source = demo_exemplar();
    CellSetParams params;
    params.cell = {160, 160};
    params.corner_colours = 2;
    params.variants = 2;
    params.seed = 1;
    REQUIRE(source.cols >= CellSet::smallest_source(params.cell).width);
    const cv::Mat lab = tilejet::synth::detail::to_lab(source);
    const CellSet set(source, lab, params);
    REQUIRE(set.size() == 36);
    CHECK(set.unmatched_blocks() == 0);
}

TEST_CASE("no two images of a set show one inside at the same place, batch-mates or not",
          "[cell_set]") {
    // Images are made two at a time (kImageBatch), and the two did not see each other's blocks:
    // where one window fitted both frames best, both copied it to the same place (two of
    // limestone's 32 images, 384 px at map seed 1, showed one inside whole). And images sharing
    // a strip took its zero-cost continuation from the source into their insides, each after
    // the other, the same-place cost notwithstanding: up to 61 % of two images' insides were
    // alike pixel for pixel on limestone at map seed 2, whose periodicity rose to 1.24.
    using tilejet::synth::detail::CellSet;
    using tilejet::synth::detail::CellSetParams;
    const cv::Mat& source = demo_exemplar();
    CellSetParams params;
    params.cell = {128, 128};
    params.variants = 2;
    const cv::Mat lab = tilejet::synth::detail::to_lab(source);
    const int frame = 128 / 10 + 1;
    const cv::Rect inside(frame, frame, 128 - 2 * frame, 128 - 2 * frame);
    for (const uint64_t seed : {1, 2, 3, 4, 5, 6, 7, 8}) {
        params.seed = seed;
        const CellSet set(source, lab, params);
        REQUIRE(set.size() == 36);
        int mates = 0, any = 0;
        for (size_t a = 0; a < set.size(); ++a)
            for (size_t b = a + 1; b < set.size(); ++b) {
                const int alike = pixels_alike(set.image(a), set.image(b), inside);
                any = std::max(any, alike);
                if (a % 2 == 0 && b == a + 1) mates = std::max(mates, alike);
            }
        INFO("map seed " << seed << ": most pixels alike at the same place of two images made "
                         << "side by side " << mates << ", of any two " << any << ", of "
                         << inside.area());
        CHECK(mates < inside.area() / 8);
        CHECK(any < inside.area() / 8);
    }
}

TEST_CASE("a cell keeps only the outer part of its frame, its own blocks take the rest",
          "[cell_set]") {
    // The two variants of one combination hold the same four strips: where both show them they
    // are alike pixel for pixel. When cells kept all of their frames, a wall showed little of
    // the source but what strips were cut from (cell_set.cpp, kept_depths()). How deep they
    // keep it wanders along the edges since session 32 (cell_layout.hpp, tested in
    // test_cell_layout.cpp); kept straight, as before, two fifths of the frame everywhere.
    using tilejet::synth::detail::CellSet;
    using tilejet::synth::detail::CellSetParams;
    const cv::Mat& source = demo_exemplar();
    const int frame = 128 / 10;  // the strips' half width
    for (const bool wandering : {false, true}) {
        CellSetParams params;
        params.cell = {128, 128};
        params.variants = 2;
        params.wandering = wandering;
        const CellSet set(source, tilejet::synth::detail::to_lab(source), params);
        REQUIRE(set.size() == 36);
        // Pixels alike, and pixels in all, at each chessboard distance from the cell's edge.
        std::vector<double> alike(size_t(frame), 0), all(size_t(frame), 0);
        for (size_t c = 0; c < 16; ++c) {
            const cv::Mat &a = set.image(c), &b = set.image(c + 16);
            for (int y = 0; y < 128; ++y)
                for (int x = 0; x < 128; ++x) {
                    const int depth = std::min({x, y, 127 - x, 127 - y});
                    if (depth >= frame) continue;
                    all[size_t(depth)] += 1;
                    alike[size_t(depth)] += a.at<cv::Vec3b>(y, x) == b.at<cv::Vec3b>(y, x);
                }
        }
        INFO((wandering ? "wandering" : "straight"));
        for (int depth = 0; depth < frame; ++depth)
            UNSCOPED_INFO("depth " << depth << ": " << alike[size_t(depth)] / all[size_t(depth)]
                                   << " alike");
        // The edge is the strips' (neighbours meet there), and so is most of the next pixels.
        CHECK(alike[0] == all[0]);
        CHECK(alike[1] > 0.5 * all[1]);
        // Past the outer two fifths of a straight frame the images are their own; a wandering
        // one keeps more in places, less in others.
        for (int depth = frame / 2; depth < frame; ++depth)
            CHECK(alike[size_t(depth)] < (wandering ? 0.35 : 0.2) * all[size_t(depth)]);
    }
}

TEST_CASE(
    "with steps smoothed, a set is still seamless for every pair and its borders are the "
    "same pixels",
    "[cell_set]") {
    BuildParams p;
    p.corner_colours = 2;
    p.variants = 2;
    p.cell_size = kCell;
    p.patches = 12;
    p.candidates = 96;
    p.seed = 3;
    p.smooth_steps = true;
    const TextureMap smooth = build_texture_map(demo_exemplar(), p);
    const TextureMap& plain = small_set();
    require_seamless(smooth);
    REQUIRE(smooth.cell_images.size() == plain.cell_images.size());
    // The same quilt (what the blocks copy does not depend on the correction), changed inside
    // only: the outer pixels neighbours meet across are the strips' own.
    size_t changed = 0;
    for (size_t m = 0; m < plain.cell_images.size(); ++m) {
        const cv::Mat& a = plain.cell_images[m].pixels;
        const cv::Mat& b = smooth.cell_images[m].pixels;
        cv::Mat differ;
        cv::absdiff(a, b, differ);
        cv::Mat inside = differ(cv::Rect(1, 1, kCell - 2, kCell - 2)).clone();
        differ(cv::Rect(1, 1, kCell - 2, kCell - 2)).setTo(0);
        INFO("image " << m);
        CHECK(cv::countNonZero(differ.reshape(1)) == 0);
        changed += cv::countNonZero(inside.reshape(1)) > 0;
    }
    // The measure can fail: most images had a step to remove.
    CHECK(changed > plain.cell_images.size() / 2);
}

TEST_CASE(
    "by default slab scans get three corner colours, cells up to 320 px four from sources "
    "of 256-511 px (else three), pattern files four, large cells two",
    "[cell_set]") {
    using tilejet::synth::detail::CellSet;
    struct Case {
        cv::Size cell, source;
        int colours;
    };
    for (const Case& c : {
             // 81 images of 640 px cells hold 33 Mpx: less than an 8192 px slab (67 Mpx), twice
             // a 4096 px one.
             Case{{640, 640}, {8192, 8192}, 3},
             Case{{640, 640}, {4096, 4096}, 2},
             Case{{640, 640}, {5760, 5760}, 2},
             Case{{640, 640}, {5800, 5800}, 3},
             // Large cells (the demo design at 360 dpi) two; up to 320 px four from sources of
             // 256 px or more (session 42; three since session 39), three from smaller ones.
             Case{{480, 480}, {1843, 1843}, 2},
             Case{{352, 352}, {1024, 1024}, 2},
             Case{{320, 320}, {511, 511}, 4},
             Case{{320, 320}, {512, 512}, 3},  // a build of four colours: over a minute
             Case{{256, 256}, {384, 384}, 4},
             Case{{256, 256}, {256, 256}, 4},
             Case{{192, 192}, {192, 192}, 3},
             Case{{128, 128}, {255, 200}, 3},
             // Sources under 128 px (pattern files): 4.
             Case{{100, 75}, {100, 75}, 4},
             Case{{128, 128}, {128, 128}, 3},
         }) {
        INFO("cell " << c.cell << ", source " << c.source);
        CHECK(CellSet::default_corner_colours(c.cell, c.source) == c.colours);
    }
    // Built by default, a design of the corpus's size has four, one variant each.
    BuildParams defaults;
    CHECK(defaults.corner_colours == 0);
    defaults.cell_size = 96;
    const TextureMap map = build_texture_map(
        load_exemplar(std::filesystem::path(TILEJET_SOURCE_DIR) / "tests/quality/corpus/gravel.png",
                      {}),
        defaults);
    CHECK(map.corner_colours == 4);
    CHECK(map.cell_images.size() == 256);
    for (const int bad : {-1, 5}) {
        defaults.corner_colours = bad;
        CHECK_THROWS_WITH(
            build_texture_map(cv::Mat(256, 256, CV_8UC3, cv::Scalar::all(90)), defaults),
            Catch::Contains("--corner-colours " + std::to_string(bad)));
    }
}
