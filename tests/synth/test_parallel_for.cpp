// parallel_for: every item once, an exception reaches the caller (never std::terminate), and
// progress is heard from the calling thread.
#include <algorithm>
#include <atomic>
#include <catch2/catch.hpp>
#include <stdexcept>
#include <vector>

#include "tilejet/synth/internal/parallel_for.hpp"

using tilejet::synth::detail::parallel_for;

TEST_CASE("parallel_for runs every item once on any number of threads", "[parallel]") {
    for (const int threads : {1, 2, 5}) {
        std::vector<std::atomic<int>> runs(257);
        parallel_for(runs.size(), threads, [&](size_t i) { ++runs[i]; });
        for (size_t i = 0; i < runs.size(); ++i) {
            INFO("item " << i << ", " << threads << " threads");
            CHECK(runs[i].load() == 1);
        }
    }
}

TEST_CASE("an exception thrown by an item reaches parallel_for's caller", "[parallel]") {
    for (const int threads : {1, 3}) {
        std::atomic<int> ran{0};
        CHECK_THROWS_WITH(parallel_for(
                              100, threads,
                              [&](size_t i) {
                                  ++ran;
                                  if (i == 7) throw std::runtime_error("item 7 failed");
                              },
                              [](size_t) {}),
                          "item 7 failed");
        CHECK(ran.load() >= 1);
    }
}

TEST_CASE("parallel_for reports progress ending at the item count", "[parallel]") {
    std::vector<size_t> heard;
    parallel_for(
        64, 2, [](size_t) {}, [&](size_t done) { heard.push_back(done); });
    REQUIRE_FALSE(heard.empty());
    CHECK(heard.back() == 64);
    CHECK(std::is_sorted(heard.begin(), heard.end()));
}
