// Convert once, copy many: rendering a converted map equals transforming every rendered pixel.

#include <catch2/catch.hpp>
#include <cstring>
#include <opencv2/core.hpp>

#include "../synth/fixtures.hpp"
#include "colour_fixtures.hpp"
#include "tilejet/colour/cmyk_map.hpp"
#include "tilejet/colour/cmyk_tiff.hpp"
#include "tilejet/synth/sampler.hpp"

using namespace tilejet;
using colour::ColourSettings;
using colour::Intent;

namespace {

ColourSettings settings(Intent intent, double limit, bool bpc) {
    ColourSettings s;
    s.output_profile = test::test_cmyk_profile();
    s.intent = intent;
    s.ink_limit_percent = limit;
    s.black_point_compensation = bpc;
    return s;
}

size_t differing_bytes(const cv::Mat& a, const cv::Mat& b) {
    REQUIRE(a.size() == b.size());
    REQUIRE(a.type() == b.type());
    size_t n = 0;
    for (int r = 0; r < a.rows; ++r)
        for (size_t i = 0; i < size_t(a.cols) * a.elemSize(); ++i)
            n += a.ptr(r)[i] != b.ptr(r)[i];
    return n;
}

}  // namespace

TEST_CASE("a CMYK render equals the per-pixel transform of the RGB render", "[colour]") {
    const synth::TextureMap& map = test::small_map();
    const synth::Region region{-70000, 123456, 200, 150};
    const cv::Mat rgb = synth::render_region(map, 21, region, 2);
    for (Intent intent : {Intent::Perceptual, Intent::RelativeColorimetric, Intent::Saturation,
                          Intent::AbsoluteColorimetric})
        for (double limit : {400.0, 300.0, 240.0})
            for (bool bpc : {false, true}) {
                const colour::CmykTransform transform(settings(intent, limit, bpc));
                cv::Mat per_pixel(rgb.size(), CV_8UC4);
                for (int y = 0; y < rgb.rows; ++y)
                    for (int x = 0; x < rgb.cols; ++x)
                        transform.convert(rgb.ptr(y) + 3 * x, per_pixel.ptr(y) + 4 * x, 1);
                const auto cmyk_map = colour::convert_map(map, transform);
                const cv::Mat rendered = synth::render_region(*cmyk_map, 21, region, 2);
                INFO("intent " << colour::intent_name(intent) << ", limit " << limit << ", bpc "
                               << bpc);
                REQUIRE(differing_bytes(rendered, per_pixel) == 0);
            }
}

TEST_CASE("no pixel exceeds the total ink limit", "[colour]") {
    for (double limit : {300.0, 260.0, 180.0}) {
        const colour::CmykTransform transform(settings(Intent::Perceptual, limit, false));
        // Every 8th level of the RGB cube, including the darkest colours that want most ink.
        cv::Mat cube(1, 33 * 33 * 33, CV_8UC3);
        int i = 0;
        for (int r = 0; r <= 256; r += 8)
            for (int g = 0; g <= 256; g += 8)
                for (int b = 0; b <= 256; b += 8)
                    cube.at<cv::Vec3b>(0, i++) = {uint8_t(std::min(r, 255)),
                                                  uint8_t(std::min(g, 255)),
                                                  uint8_t(std::min(b, 255))};
        const cv::Mat cmyk = transform.to_cmyk(cube);
        const int max_units = int(limit / 100.0 * 255.0);
        int worst = 0;
        for (int p = 0; p < cmyk.cols; ++p) {
            const cv::Vec4b v = cmyk.at<cv::Vec4b>(0, p);
            worst = std::max(worst, v[0] + v[1] + v[2] + v[3]);
        }
        INFO("limit " << limit << "% = " << max_units << " units, worst " << worst);
        REQUIRE(worst <= max_units);
        // The limit bites: the darkest colours would use more without it.
        REQUIRE(worst >= max_units - 8);
    }
}

TEST_CASE("a converted map is the same plane in other inks, pipelines are told apart by key",
          "[colour]") {
    const synth::TextureMap& map = test::small_map();
    const colour::CmykTransform a(settings(Intent::Perceptual, 300, false));
    const colour::CmykTransform b(settings(Intent::Perceptual, 300, false));
    const colour::CmykTransform c(settings(Intent::RelativeColorimetric, 300, false));
    REQUIRE(a.key() == b.key());
    REQUIRE(a.key() != c.key());
    const auto converted = colour::convert_map(map, a);
    REQUIRE(converted->id == map.id);  // same plane: activation must not change with the inks
    REQUIRE(converted->source.type() == CV_8UC4);
    REQUIRE(converted->cell_images.size() == map.cell_images.size());
}

TEST_CASE("a CMYK TIFF reads back with its pixels and embedded profile", "[colour]") {
    test::TempDir dir;
    const colour::CmykTransform transform(settings(Intent::Perceptual, 300, true));
    const auto cmyk_map = colour::convert_map(test::small_map(), transform);
    const cv::Mat cmyk = synth::render_region(*cmyk_map, 4, {0, 0, 97, 61});
    colour::write_cmyk_tiff(cmyk, transform.output_profile_bytes(), dir / "tile.tif");
    const colour::CmykTiff back = colour::read_cmyk_tiff(dir / "tile.tif");
    REQUIRE(differing_bytes(back.cmyk, cmyk) == 0);
    REQUIRE(back.icc_profile == transform.output_profile_bytes());
    REQUIRE_FALSE(back.icc_profile.empty());
}

TEST_CASE("the soft proof of a CMYK render stays close to the design", "[colour]") {
    const colour::CmykTransform transform(settings(Intent::RelativeColorimetric, 400, true));
    const cv::Mat rgb = synth::render_region(test::small_map(), 2, {0, 0, 128, 128});
    const cv::Mat proof = transform.proof(transform.to_cmyk(rgb));
    // The demo stone is well inside a press gamut: the round trip should move it little.
    cv::Mat diff;
    cv::absdiff(rgb, proof, diff);
    const cv::Scalar d = cv::mean(diff);
    INFO("mean |difference| per channel " << d[0] << " " << d[1] << " " << d[2]);
    REQUIRE(d[0] < 12);
    REQUIRE(d[1] < 12);
    REQUIRE(d[2] < 12);
}
