// Properties of the online sampler's patch activation (docs/design.md section 3), checked by
// rasterizing masks independently of the renderer.

#include <catch2/catch.hpp>
#include <cmath>
#include <opencv2/core.hpp>
#include <random>

#include "fixtures.hpp"
#include "tilejet/synth/internal/active_set.hpp"
#include "tilejet/synth/sampler.hpp"

using namespace tilejet::synth;
using tilejet::test::small_map;

namespace {

// Counts, on a canvas around cell (i, j), how many shown patches cover each pixel: those of
// the A cell (i, j) and of its four B neighbours. Returns the largest count.
int max_coverage(const TextureMap& map, uint64_t seed, CellIndex a_cell) {
    const int cw = map.cell_width, ch = map.cell_height;
    const int64_t ox = (a_cell.i - 2) * cw, oy = (a_cell.j - 2) * ch;  // canvas origin
    cv::Mat count(5 * ch, 5 * cw, CV_8U, cv::Scalar(0));
    auto paint = [&](CellType type, CellIndex cell) {
        const PatchSet& set = map.cell_images.front().set(type);
        for (uint16_t k : active_patches(map, seed, type, cell)) {
            const Patch& p = set.patches[k];
            for (int y = 0; y < p.height; ++y)
                for (int x = 0; x < p.width; ++x)
                    if (p.covers(x, y)) {
                        const int64_t cx = cell.i * cw + p.x + x - ox,
                                      cy = cell.j * ch + p.y + y - oy;
                        ++count.at<uint8_t>(int(cy), int(cx));
                    }
        }
    };
    paint(CellType::A, a_cell);
    for (auto [di, dj] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}})
        paint(CellType::B, {a_cell.i + di, a_cell.j + dj});
    double max = 0;
    cv::minMaxLoc(count, nullptr, &max);
    return int(max);
}

}  // namespace

TEST_CASE("no pixel is covered by more than one shown patch", "[sampler][property]") {
    const TextureMap& map = small_map();
    std::mt19937_64 rng(2024);
    std::uniform_int_distribution<int64_t> cell_coord(-(int64_t(1) << 24), int64_t(1) << 24);
    int worst = 0;
    for (int n = 0; n < 3000; ++n) {
        const uint64_t seed = rng() % 4 == 0 ? uint64_t(n) : rng();
        int64_t i = cell_coord(rng), j = cell_coord(rng);
        if ((i + j) & 1) ++i;  // an A cell
        worst = std::max(worst, max_coverage(map, seed, {i, j}));
        if (worst > 1) {
            INFO("seed " << seed << " cell " << i << "," << j);
            REQUIRE(worst <= 1);
        }
    }
    REQUIRE(worst == 1);  // patches were shown at all
}

TEST_CASE("every shown patch lies in its own cell's diamond", "[sampler][property]") {
    const TextureMap& map = small_map();
    std::mt19937_64 rng(77);
    for (int n = 0; n < 300; ++n) {
        const CellType type = n % 2 ? CellType::B : CellType::A;
        int64_t i = int64_t(rng() % 2001) - 1000, j = int64_t(rng() % 2001) - 1000;
        if (((i + j) & 1) != int64_t(type)) ++j;
        const CellIndex cell{i, j};
        const PatchSet& set = map.cell_images.front().set(type);
        for (uint16_t k : active_patches(map, n, type, cell)) {
            const Patch& p = set.patches[k];
            for (int y = 0; y < p.height; ++y)
                for (int x = 0; x < p.width; ++x)
                    if (p.covers(x, y)) {
                        const int64_t px = i * map.cell_width + p.x + x,
                                      py = j * map.cell_height + p.y + y;
                        REQUIRE(diamond_cell(map, type, px, py) == cell);
                    }
        }
    }
}

TEST_CASE("activation frequency matches eta", "[sampler][statistics]") {
    const TextureMap& map = small_map();
    const PatchSet& set = map.cell_images.front().a;
    const double n = double(set.size());
    const double eta = map.build.active_per_cell / n;  // docs/design.md section 3.2
    std::mt19937_64 rng(99);
    const int cells = 20000;
    std::vector<int> hits(set.size(), 0);
    std::vector<uint16_t> active;
    size_t total = 0;
    for (int c = 0; c < cells; ++c) {
        const uint64_t key = tilejet::synth::detail::cell_key(map.id64(), rng(), 0, CellType::A,
                                                              int64_t(rng()), int64_t(rng()));
        tilejet::synth::detail::activate(set, key, active);
        total += active.size();
        for (uint16_t k : active)
            ++hits[k];
    }
    // Overall rate: binomial with cells * n trials; allow five standard deviations.
    const double trials = cells * n;
    const double rate = double(total) / trials;
    const double sigma = std::sqrt(eta * (1 - eta) / trials);
    INFO("rate " << rate << " eta " << eta << " sigma " << sigma);
    REQUIRE(std::abs(rate - eta) < 5 * sigma);

    // Every patch equally likely: chi-square over patches, against mean + 5 sd of its
    // distribution (n - 1 degrees of freedom).
    const double expected = cells * eta;
    double chi2 = 0;
    for (int h : hits)
        chi2 += (h - expected) * (h - expected) / (expected * (1 - eta));
    const double dof = n - 1;
    INFO("chi2 " << chi2 << " dof " << dof);
    REQUIRE(chi2 < dof + 5 * std::sqrt(2 * dof));
}

TEST_CASE("overlap removal leaves no two overlapping patches and keeps the rest", "[sampler]") {
    const TextureMap& map = small_map();
    const PatchSet& set = map.cell_images.front().b;
    std::mt19937_64 rng(3);
    for (int n = 0; n < 500; ++n) {
        std::vector<uint16_t> active;
        tilejet::synth::detail::activate(set, rng(), active);
        const std::vector<uint16_t> before = active;
        tilejet::synth::detail::remove_overlaps(set, active);
        for (size_t a = 0; a < active.size(); ++a)
            for (size_t b = a + 1; b < active.size(); ++b)
                REQUIRE_FALSE(set.overlaps(active[a], active[b]));
        // A patch that overlapped nothing in the activated set is never dropped.
        for (uint16_t k : before) {
            bool lonely = true;
            for (uint16_t o : before)
                lonely &= (o == k) || !set.overlaps(k, o);
            if (lonely) REQUIRE(std::find(active.begin(), active.end(), k) != active.end());
        }
    }
}

TEST_CASE("overlap removal drops exactly what the rule of design section 3.3 drops", "[sampler]") {
    // The rule written out plainly: while any two kept patches overlap, drop the kept patch with
    // the most overlaps among the kept ones, the lower index on a tie. Every rendered byte
    // depends on it, so the fast version must agree on every set, small or larger than 64.
    const auto by_the_rule = [](const PatchSet& set, std::vector<uint16_t> active) {
        for (;;) {
            size_t worst = active.size();
            size_t most = 0;
            for (size_t a = 0; a < active.size(); ++a) {
                size_t degree = 0;
                for (size_t b = 0; b < active.size(); ++b)
                    degree += a != b && set.overlaps(active[a], active[b]);
                if (degree > most) most = degree, worst = a;
            }
            if (worst == active.size()) return active;
            active.erase(active.begin() + std::ptrdiff_t(worst));
        }
    };
    const TextureMap& map = small_map();
    std::mt19937_64 rng(11);
    for (const PatchSet* set : {&map.cell_images.front().a, &map.cell_images.front().b}) {
        size_t dropped = 0;
        for (int n = 0; n < 2000; ++n) {
            // Sizes around the usual ten, and well past one 64-bit mask.
            const size_t want = n % 4 == 0 ? 2 + rng() % 150 : 2 + rng() % 30;
            std::vector<uint16_t> active;
            for (size_t k = 0; k < set->size(); ++k)
                if (rng() % set->size() < want) active.push_back(uint16_t(k));
            std::vector<uint16_t> fast = active;
            tilejet::synth::detail::remove_overlaps(*set, fast);
            INFO("set of " << active.size());
            REQUIRE(fast == by_the_rule(*set, active));
            dropped += active.size() - fast.size();
        }
        REQUIRE(dropped > 1000);  // the sets overlapped enough to test the choice
    }
}
