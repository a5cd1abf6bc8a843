// The one rule for means and percentiles of every report (statistics.hpp).

#include <catch2/catch.hpp>
#include <numeric>

#include "tilejet/colour/statistics.hpp"

using tilejet::colour::percentile;
using tilejet::colour::summarize;

TEST_CASE("percentiles are nearest-rank: the ceil(p n)-th smallest value", "[quality]") {
    std::vector<double> twenty(20);
    std::iota(twenty.begin(), twenty.end(), 1.0);
    std::reverse(twenty.begin(), twenty.end());  // the order given does not matter
    CHECK(percentile(twenty, 0.95) == 19);       // 0.95 * 20 = 19
    CHECK(percentile(twenty, 0.96) == 20);       // 19.2, rounded up
    CHECK(percentile(twenty, 0.5) == 10);
    CHECK(percentile(twenty, 1.0) == 20);
    CHECK(percentile(twenty, 0.0) == 1);  // the smallest, not below it
    std::vector<float> hundred(100);
    std::iota(hundred.begin(), hundred.end(), 1.0f);
    CHECK(percentile(hundred, 0.99) == 99);
    std::vector<double> one{4.5}, none;
    CHECK(percentile(one, 0.95) == 4.5);
    CHECK(percentile(none, 0.95) == 0);
}

TEST_CASE("a summary gives count, mean, percentile and maximum", "[quality]") {
    std::vector<double> v{3, 1, 4, 1, 5, 9, 2, 6};
    const auto s = summarize(v, 0.75);
    CHECK(s.count == 8);
    CHECK(s.mean == Approx(31.0 / 8));
    CHECK(s.percentile == 5);  // sorted 1 1 2 3 4 5 6 9: the 6th
    CHECK(s.max == 9);
    std::vector<double> none;
    const auto empty = summarize(none, 0.95);
    CHECK(empty.count == 0);
    CHECK(empty.mean == 0);
    CHECK(empty.max == 0);
}
