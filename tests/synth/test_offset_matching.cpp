// Block searches (offset_matching.hpp): where in the source a new piece copies from, and the
// coarse-to-fine search of large sources.

#include <catch2/catch.hpp>
#include <opencv2/imgproc.hpp>

#include "offset_matching.hpp"

using namespace tilejet::synth::detail;

namespace {

// A soft random source, like a small photo enlarged many times (the slab scans): every place is
// its own, and no two windows match exactly.
cv::Mat soft_source(int side, uint64_t seed) {
    cv::Mat noise(side / 16, side / 16, CV_32FC3);
    cv::RNG rng(seed);
    rng.fill(noise, cv::RNG::UNIFORM, cv::Scalar::all(0), cv::Scalar(100, 60, 60));
    cv::Mat source;
    cv::resize(noise, source, {side, side}, 0, 0, cv::INTER_CUBIC);
    return source;
}

// The overlap of a block: an L of `overlap` px along its top and left.
cv::Mat l_mask(cv::Size piece, int overlap) {
    cv::Mat mask(piece, CV_32F, cv::Scalar(0));
    mask(cv::Rect(0, 0, piece.width, overlap)).setTo(1);
    mask(cv::Rect(0, 0, overlap, piece.height)).setTo(1);
    return mask;
}

}  // namespace

TEST_CASE("a coarse-to-fine search finds a piece's own place anywhere in a large source",
          "[offset]") {
    const cv::Mat source = soft_source(2048, 3);
    const cv::Mat coarse = coarse_source(source, 2);
    REQUIRE(coarse.size() == cv::Size(1024, 1024));
    const cv::Size piece(160, 160);
    const cv::Mat mask = l_mask(piece, 32);
    OffsetSearch search{source, {}, 16, 384, {}, &coarse, 2};
    REQUIRE(searches_coarse_to_fine(search, piece));
    // Places far apart, none a multiple of the factor: the full-resolution step must find
    // the exact one, not the coarse pixel's.
    int found_coarse = 0, found_window = 0;
    for (const cv::Point truth : {cv::Point(1613, 87), cv::Point(41, 1777), cv::Point(999, 1001),
                                  cv::Point(1887, 1887), cv::Point(0, 0), cv::Point(701, 1333)}) {
        const cv::Mat old = source(cv::Rect(truth, piece)).clone();
        Rng rng(uint64_t(truth.x) * 7919 + uint64_t(truth.y));
        const auto best = ranked_offsets(search, old, mask, rng, 4);
        REQUIRE(best.size() == 4);
        found_coarse += best.front() == truth;
        // The random window alone, as before: it holds the place about once in twenty.
        OffsetSearch window_only{source, {}, 16, 384, {}, nullptr, 1};
        Rng rng2(uint64_t(truth.x) * 7919 + uint64_t(truth.y));
        const auto windowed = ranked_offsets(window_only, old, mask, rng2, 1);
        found_window += !windowed.empty() && windowed.front() == truth;
    }
    CHECK(found_coarse == 6);
    CHECK(found_window < 6);
}

TEST_CASE("a random window that holds a good match is searched as before", "[offset]") {
    // A soft 256 px pattern laid 8 x 8, and pieces of it with noise of their own: every window
    // of 384 positions holds a match as good as any, so the coarse-to-fine search has nothing
    // better to offer.
    const cv::Mat tile = soft_source(256, 5);
    cv::Mat source;
    cv::repeat(tile, 8, 8, source);
    const cv::Mat coarse = coarse_source(source, 2);
    const cv::Size piece(128, 96);
    const cv::Mat mask = l_mask(piece, 24);
    const OffsetSearch with{source, {}, 12, 384, {}, &coarse, 2};
    const OffsetSearch without{source, {}, 12, 384, {}, nullptr, 1};
    REQUIRE(searches_coarse_to_fine(with, piece));
    for (const cv::Point at : {cv::Point(1200, 640), cv::Point(77, 1501), cv::Point(1900, 3)}) {
        cv::Mat old = source(cv::Rect(at, piece)).clone(), noise(piece, CV_32FC3);
        cv::RNG(uint64_t(at.y))
            .fill(noise, cv::RNG::NORMAL, cv::Scalar::all(0), cv::Scalar::all(2));
        old += noise;
        Rng a(uint64_t(at.x)), b(uint64_t(at.x));
        const auto found = ranked_offsets(with, old, mask, a, 6);
        CHECK(found == ranked_offsets(without, old, mask, b, 6));
        REQUIRE_FALSE(found.empty());
        // The best is a copy of the piece's own place (or one pattern away).
        CHECK((found.front().x - at.x) % 256 == 0);
        CHECK((found.front().y - at.y) % 256 == 0);
    }
}

TEST_CASE("a coarse-to-fine search keeps to the allowed offsets and to the penalty", "[offset]") {
    const cv::Mat source = soft_source(2048, 9);
    const cv::Mat coarse = coarse_source(source, 2);
    const cv::Size piece(160, 160);
    const cv::Mat mask = l_mask(piece, 32);
    const cv::Point truth(1500, 400);
    const cv::Mat old = source(cv::Rect(truth, piece)).clone();
    OffsetSearch search{source, [&](cv::Point at) { return at != truth; }, 16, 384, {}, &coarse, 2};
    Rng rng(2);
    auto best = ranked_offsets(search, old, mask, rng, 3);
    REQUIRE_FALSE(best.empty());
    for (const cv::Point p : best)
        CHECK(p != truth);
    // A penalty on the true place's neighbourhood sends the search elsewhere.
    search.allowed = {};
    search.add_penalty = [&](const cv::Rect& area, cv::Mat& costs) {
        for (int y = 0; y < costs.rows; ++y)
            for (int x = 0; x < costs.cols; ++x) {
                const cv::Point at = area.tl() + cv::Point(x, y);
                if (std::abs(at.x - truth.x) < 40 && std::abs(at.y - truth.y) < 40)
                    costs.at<float>(y, x) += 1e12f;
            }
    };
    best = ranked_offsets(search, old, mask, rng, 3);
    REQUIRE_FALSE(best.empty());
    for (const cv::Point p : best)
        CHECK(std::max(std::abs(p.x - truth.x), std::abs(p.y - truth.y)) >= 40);
}

TEST_CASE("small sources and small pieces are searched as before", "[offset]") {
    const cv::Mat source = soft_source(2048, 4);
    const cv::Mat coarse = coarse_source(source, 8);
    OffsetSearch search{source, {}, 8, 384, {}, &coarse, 8};
    // Eight times smaller, a 48 px piece keeps 6 px: too few to match on.
    CHECK_FALSE(searches_coarse_to_fine(search, {48, 48}));
    CHECK(searches_coarse_to_fine(search, {128, 128}));
    // A window as large as the source: searched whole, as before.
    search.window = 2048;
    CHECK_FALSE(searches_coarse_to_fine(search, {128, 128}));
    search.window = 384;
    search.coarse = nullptr;
    CHECK_FALSE(searches_coarse_to_fine(search, {128, 128}));
}
