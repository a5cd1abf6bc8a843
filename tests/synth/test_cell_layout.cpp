// Where a cell image's own blocks go (cell_layout.hpp): a kept frame whose depth wanders within
// its bounds, and joints that move while every pair of neighbours keeps its overlap.

#include <algorithm>
#include <catch2/catch.hpp>
#include <numeric>
#include <set>

#include "cell_layout.hpp"

using namespace tilejet::synth::detail;

TEST_CASE("a wandering kept frame stays within its depths and reaches across them",
          "[cell_layout]") {
    const cv::Size cell(256, 200);
    const KeptDepths depths{2, 25, 10, 10};
    Rng rng(7);
    const KeptFrame f = kept_frame(cell, depths, rng);
    REQUIRE(f.top.size() == 256);
    REQUIRE(f.left.size() == 200);
    for (const auto* edge : {&f.top, &f.bottom, &f.left, &f.right}) {
        const int length = int(edge->size());
        std::set<int> seen;
        for (int t = 0; t < length; ++t) {
            const int d = (*edge)[size_t(t)];
            CHECK(d >= depths.least);
            CHECK(d <= depths.most);
            // The corner cores' quarters need room for the cut round them.
            if (t < depths.corner_reach || t >= length - depths.corner_reach)
                CHECK(d >= depths.corner_least);
            // Smooth: no step of more than a few px from one place to the next, but where the
            // corners' least ends.
            if (t > 0 && t != depths.corner_reach && t != length - depths.corner_reach)
                CHECK(std::abs(d - (*edge)[size_t(t - 1)]) <= 3);
            seen.insert(d);
        }
        // It wanders: shallow and deep along every edge, not one depth.
        CHECK(*seen.begin() <= 8);
        CHECK(*seen.rbegin() >= 18);
    }
    // The same draws give the same frame; other draws another.
    Rng again(7), other(8);
    CHECK(kept_frame(cell, depths, again).top == f.top);
    CHECK(kept_frame(cell, depths, other).top != f.top);
    // keeps(): within the depth at each place, not past it.
    CHECK(f.keeps({10, f.top[10] - 1}, cell));
    CHECK_FALSE(f.keeps({128, 100}, cell));
}

TEST_CASE("a kept frame whose least is its most is one depth, more near the corners",
          "[cell_layout]") {
    Rng rng(3);
    const KeptFrame f = kept_frame({128, 128}, {4, 4, 6, 6}, rng);
    CHECK(f.top[64] == 4);
    CHECK(f.left[3] == 6);
    CHECK(f.right[125] == 6);
    CHECK(f.keeps({64, 3}, {128, 128}));
    CHECK_FALSE(f.keeps({64, 4}, {128, 128}));
}

TEST_CASE("jittered joints keep every overlap and the outer ends", "[cell_layout]") {
    const auto spans = block_spans(0, 256, 152, 48);
    REQUIRE(spans.size() == 2);
    std::set<int> joints;
    for (uint64_t seed = 1; seed <= 50; ++seed) {
        Rng rng(seed);
        const auto moved = jittered_spans(spans, 34, rng);
        REQUIRE(moved.size() == spans.size());
        CHECK(moved.front().first == 0);
        CHECK(moved.back().second == 256);
        for (size_t i = 1; i < moved.size(); ++i) {
            CHECK(moved[i - 1].second - moved[i].first == spans[i - 1].second - spans[i].first);
            CHECK(std::abs(moved[i].first - spans[i].first) <= 34);
            CHECK(moved[i].first > moved[i - 1].first);
        }
        joints.insert(moved[1].first);
    }
    // The joint lies at many places, not one.
    CHECK(joints.size() > 20);
}
