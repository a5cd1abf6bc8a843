#include <catch2/catch.hpp>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "../synth/fixtures.hpp"
#include "tilejet/quality/patch_labels.hpp"
#include "tilejet/quality/wall.hpp"
#include "tilejet/synth/quilt.hpp"
#include "tilejet/synth/sampler.hpp"

using namespace tilejet;

TEST_CASE("patch labels agree with render_region", "[quality]") {
    const synth::TextureMap& map = test::small_map();
    const cv::Mat& cell = map.cell_images.front().pixels;
    for (const synth::Region region :
         {synth::Region{-70, 33, 300, 200}, synth::Region{(int64_t(1) << 31) - 300, -5, 300, 90}}) {
        const cv::Mat rgb = synth::render_region(map, 9, region, 2);
        const cv::Mat labels = quality::render_patch_labels(map, 9, region);
        REQUIRE(labels.size() == rgb.size());
        size_t labelled = 0;
        std::map<int32_t, size_t> pixels_of;
        for (int y = 0; y < rgb.rows; ++y)
            for (int x = 0; x < rgb.cols; ++x) {
                const int64_t px = region.x + x, py = region.y + y;
                const int32_t id = labels.at<int32_t>(y, x);
                const cv::Vec3b got = rgb.at<cv::Vec3b>(y, x);
                if (id == 0) {
                    // Unlabelled pixels show the cell image, wherever they are.
                    const cv::Vec3b want = cell.at<cv::Vec3b>(
                        int(((py % map.cell_height) + map.cell_height) % map.cell_height),
                        int(((px % map.cell_width) + map.cell_width) % map.cell_width));
                    REQUIRE(got == want);
                    continue;
                }
                ++labelled;
                ++pixels_of[id];
            }
        CHECK(labelled > 0);
        CHECK(pixels_of.size() > 3);  // several patches in a region of several cells
    }
}

TEST_CASE("labels change exactly where render_region switches between cell image and patch",
          "[quality]") {
    const synth::TextureMap& map = test::small_map();
    const cv::Mat& cell = map.cell_images.front().pixels;
    const synth::Region region{1000, -2000, 256, 256};
    const cv::Mat rgb = synth::render_region(map, 4, region, 1);
    const cv::Mat labels = quality::render_patch_labels(map, 4, region);
    size_t differs = 0, differs_labelled = 0;
    for (int y = 0; y < rgb.rows; ++y)
        for (int x = 0; x < rgb.cols; ++x) {
            const cv::Vec3b want = cell.at<cv::Vec3b>(int((region.y + y) % 64 + 64) % 64,
                                                      int((region.x + x) % 64 + 64) % 64);
            if (rgb.at<cv::Vec3b>(y, x) == want) continue;
            ++differs;
            differs_labelled += labels.at<int32_t>(y, x) != 0;
        }
    REQUIRE(differs > 1000);
    CHECK(differs_labelled == differs);  // no pixel changes by a patch without a label
}

TEST_CASE("quilting provenance names the exemplar pixel of every output pixel", "[quality]") {
    const cv::Mat& exemplar = test::demo_exemplar();
    const synth::QuiltedImage q = synth::quilt_texture(exemplar, {150, 110}, 8, 32);
    REQUIRE(q.rgb.size() == cv::Size(150, 110));
    size_t mismatches = 0;
    for (int y = 0; y < q.rgb.rows; ++y)
        for (int x = 0; x < q.rgb.cols; ++x) {
            const int32_t i = q.provenance.at<int32_t>(y, x);
            mismatches += q.rgb.at<cv::Vec3b>(y, x) !=
                          exemplar.at<cv::Vec3b>(i / exemplar.cols, i % exemplar.cols);
        }
    CHECK(mismatches == 0);
    // Seams between blocks exist, but most neighbours are copied together.
    const cv::Mat seams = quality::seams_from_provenance(q.provenance, exemplar.cols);
    const double share = double(cv::countNonZero(seams)) / double(seams.total());
    CHECK(share > 0.005);
    CHECK(share < 0.3);
}

// Three bytes hold the indices of 2^24 pixels; a slab scan past that is quilted a second time
// for the higher bits. Were the two quilts to differ, neighbours copied together would not
// come out as neighbours in the exemplar, and seams would be everywhere.
TEST_CASE("quilting provenance names pixels past 2^24 of a slab-sized exemplar", "[quality]") {
    // Half its pixels lie past 2^24. Quilting searches one random window of the exemplar per
    // quilt: the first seed whose window lies there (5, as the quilt's choices stand: the
    // search starts there, and goes on should they change).
    cv::Mat noise(4096 / 8, 8192 / 8, CV_8UC3), exemplar;
    cv::RNG(7).fill(noise, cv::RNG::UNIFORM, 0, 256);
    cv::resize(noise, exemplar, {8192, 4096}, 0, 0, cv::INTER_CUBIC);  // blobs 8 px across
    synth::QuiltedImage q;
    std::int32_t largest = 0;
    for (std::uint64_t seed = 5; seed <= 16 && largest < (1 << 24); ++seed) {
        q = synth::quilt_texture(exemplar, {256, 256}, seed, 64);
        largest = 0;
        for (int y = 0; y < q.provenance.rows; ++y)
            for (int x = 0; x < q.provenance.cols; ++x)
                largest = std::max(largest, q.provenance.at<int32_t>(y, x));
    }
    REQUIRE(largest >= (1 << 24));
    CHECK(largest < std::int32_t(exemplar.total()));
    const cv::Mat seams = quality::seams_from_provenance(q.provenance, exemplar.cols);
    CHECK(double(cv::countNonZero(seams)) / double(seams.total()) < 0.3);
}

// The eval's baselines quilt a slab scan with blocks of a quarter of its side (2048 px for an
// 8192 px one), more than the 1024 px window the block search used to look in: it failed.
TEST_CASE("quilting with blocks larger than the search window looks in a larger one", "[quality]") {
    cv::Mat noise(2400 / 16, 2400 / 16, CV_8UC3), exemplar;
    cv::RNG(3).fill(noise, cv::RNG::UNIFORM, 0, 256);
    cv::resize(noise, exemplar, {2400, 2400}, 0, 0, cv::INTER_CUBIC);
    const synth::QuiltedImage q = synth::quilt_texture(exemplar, {1800, 1800}, 2, 1100);
    REQUIRE(q.rgb.size() == cv::Size(1800, 1800));
    const cv::Mat seams = quality::seams_from_provenance(q.provenance, exemplar.cols);
    CHECK(double(cv::countNonZero(seams)) / double(seams.total()) < 0.05);
}
