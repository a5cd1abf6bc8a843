// Exemplars as engineers bring them: odd formats work, broken ones fail with a clear message.

#include <zlib.h>

#include <catch2/catch.hpp>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "fixtures.hpp"
#include "profile_files.hpp"
#include "tilejet/synth/build.hpp"
#include "tilejet/synth/exemplar.hpp"
#include "tilejet/synth/sampler.hpp"

using namespace tilejet::synth;
using Catch::Matchers::Contains;
using tilejet::test::demo_exemplar;
using tilejet::test::TempDir;

namespace {

BuildParams quick_params() {
    BuildParams p;
    p.corner_colours = 1;
    p.cell_size = 32;
    p.patches = 40;
    p.candidates = 400;
    return p;
}

std::string load_error(const std::filesystem::path& path) {
    try {
        load_exemplar(path, {});
    } catch (const SynthError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("unreadable, empty and undecodable exemplars fail naming the file", "[exemplar]") {
    TempDir dir;
    REQUIRE_THAT(load_error(dir / "missing.png"),
                 Contains("missing.png") && Contains("cannot read"));
    tilejet::test::write_file(dir / "empty.png", "");
    REQUIRE_THAT(load_error(dir / "empty.png"), Contains("empty.png") && Contains("empty"));
    tilejet::test::write_file(dir / "junk.png", "this is not an image at all");
    REQUIRE_THAT(load_error(dir / "junk.png"), Contains("junk.png") && Contains("cannot decode"));
    std::vector<uchar> png;
    cv::imencode(".png", demo_exemplar(), png);
    tilejet::test::write_file(dir / "cut.png", std::string(png.begin(), png.begin() + 200));
    REQUIRE_THAT(load_error(dir / "cut.png"), Contains("cut.png"));
}

TEST_CASE("a 1x1 exemplar is refused with its size", "[exemplar]") {
    TempDir dir;
    cv::imwrite((dir / "dot.png").string(), cv::Mat(1, 1, CV_8UC3, cv::Scalar(1, 2, 3)));
    REQUIRE_THAT(load_error(dir / "dot.png"), Contains("dot.png") && Contains("1x1"));
}

TEST_CASE("a grey-only exemplar builds a map that renders grey", "[exemplar]") {
    TempDir dir;
    cv::Mat grey;
    cv::cvtColor(demo_exemplar(), grey, cv::COLOR_RGB2GRAY);
    cv::imwrite((dir / "grey.png").string(), grey);
    const cv::Mat loaded = load_exemplar(dir / "grey.png", {});
    REQUIRE(loaded.type() == CV_8UC3);
    const TextureMap map = build_texture_map(loaded, quick_params());
    const cv::Mat out = render_region(map, 1, {0, 0, 64, 64});
    for (int y = 0; y < out.rows; ++y)
        for (int x = 0; x < out.cols; ++x) {
            const cv::Vec3b p = out.at<cv::Vec3b>(y, x);
            REQUIRE((p[0] == p[1] && p[1] == p[2]));
        }
}

TEST_CASE("a flat single-colour exemplar still builds a valid map", "[exemplar]") {
    const cv::Mat flat(96, 96, CV_8UC3, cv::Scalar(120, 80, 40));
    const TextureMap map = build_texture_map(flat, quick_params());
    const cv::Mat out = render_region(map, 1, {-50, -50, 100, 100});
    REQUIRE(cv::norm(out, cv::Mat(100, 100, CV_8UC3, cv::Scalar(120, 80, 40)), cv::NORM_INF) == 0);
}

TEST_CASE("a 16-bit exemplar loads as its 8-bit equivalent", "[exemplar]") {
    TempDir dir;
    cv::Mat bgr16;
    cv::cvtColor(demo_exemplar(), bgr16, cv::COLOR_RGB2BGR);
    bgr16.convertTo(bgr16, CV_16UC3, 257.0);
    cv::imwrite((dir / "deep.png").string(), bgr16);
    const cv::Mat loaded = load_exemplar(dir / "deep.png", {});
    REQUIRE(loaded.type() == CV_8UC3);
    REQUIRE(cv::norm(loaded, demo_exemplar(), cv::NORM_INF) <= 1);
}

namespace {

// A whole, valid PNG `side` px square of fine grey stripes (one bit a pixel: 50 MB of pixels
// at 20000 px, deflated to a few hundred kB), written chunk by chunk: from OpenCV, a 1.2 GB
// RGB image took 15 s to write.
std::string striped_png(uint32_t side) {
    const auto be32 = [](uint32_t v) {
        return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
    };
    // Bit depth 1, greyscale, deflate, adaptive filtering, no interlace.
    const std::string header = be32(side) + be32(side) + std::string("\x01\0\0\0\0", 5);
    std::string row(1 + (side + 7) / 8, '\x55');
    row[0] = 0;  // filter: none
    z_stream z{};
    REQUIRE(deflateInit(&z, Z_BEST_SPEED) == Z_OK);
    std::string data;
    std::vector<Bytef> out(1 << 16);
    for (uint32_t y = 0; y < side; ++y) {
        z.next_in = reinterpret_cast<Bytef*>(row.data());
        z.avail_in = uInt(row.size());
        do {
            z.next_out = out.data();
            z.avail_out = uInt(out.size());
            deflate(&z, y + 1 == side ? Z_FINISH : Z_NO_FLUSH);
            data.append(reinterpret_cast<const char*>(out.data()), out.size() - z.avail_out);
        } while (z.avail_out == 0);
    }
    deflateEnd(&z);
    using tilejet::test::png_chunk;
    return "\x89PNG\r\n\x1a\n" + png_chunk("IHDR", header) + png_chunk("IDAT", data) +
           png_chunk("IEND", "");
}

}  // namespace

TEST_CASE("a huge exemplar is refused with its size, without a crash", "[exemplar]") {
    TempDir dir;
    tilejet::test::write_file(dir / "huge.png", striped_png(20000));
    // The file is whole: OpenCV reads a smaller one of the same making.
    tilejet::test::write_file(dir / "small.png", striped_png(64));
    const cv::Mat small = cv::imread((dir / "small.png").string(), cv::IMREAD_GRAYSCALE);
    REQUIRE(small.size() == cv::Size(64, 64));
    REQUIRE(small.at<uint8_t>(0, 1) != small.at<uint8_t>(0, 0));
    REQUIRE_THAT(load_error(dir / "huge.png"), Contains("huge.png") && Contains("20000x20000"));
}

TEST_CASE("build parameters out of range are refused by name", "[exemplar]") {
    BuildParams p = quick_params();
    p.cell_size = 4000;
    REQUIRE_THROWS_WITH(build_texture_map(demo_exemplar(), p), Contains("--cell"));
    p = quick_params();
    p.patches = 1;
    REQUIRE_THROWS_WITH(build_texture_map(demo_exemplar(), p), Contains("--patches"));
    p = quick_params();
    p.candidates = 10;
    REQUIRE_THROWS_WITH(build_texture_map(demo_exemplar(), p), Contains("--candidates"));
}

TEST_CASE("an embedded profile reaches the conversion as the file holds it", "[exemplar][icc]") {
    TempDir dir;
    const std::string icc = tilejet::test::file_text(tilejet::test::kAdobeRgbProfile);
    const cv::Mat swatches = tilejet::test::saturated_swatches();
    tilejet::test::write_file(dir / "adobe.png", tilejet::test::png_with_profile(swatches, icc));
    tilejet::test::write_file(dir / "adobe.jpg", tilejet::test::jpeg_with_profile(swatches, icc));
    for (const char* file : {"adobe.png", "adobe.jpg"}) {
        std::vector<uint8_t> seen;
        std::string seen_name;
        const cv::Mat loaded = load_exemplar(
            dir / file,
            [&](cv::Mat& rgb, const std::vector<uint8_t>& profile, const std::string& name) {
                seen = profile;
                seen_name = name;
                rgb.setTo(cv::Scalar(1, 2, 3));  // what the conversion gives is what loads
            });
        CHECK(std::string(seen.begin(), seen.end()) == icc);
        CHECK_THAT(seen_name, Contains(file));
        REQUIRE(cv::norm(loaded, cv::Mat(32, 32, CV_8UC3, cv::Scalar(1, 2, 3)), cv::NORM_INF) == 0);
    }
    // Without a conversion, a file with a profile is refused rather than taken as sRGB.
    REQUIRE_THAT(load_error(dir / "adobe.png"), Contains("adobe.png") && Contains("ICC profile"));
}

TEST_CASE("a damaged embedded profile is refused naming the file", "[exemplar][icc]") {
    TempDir dir;
    const cv::Mat swatches = tilejet::test::saturated_swatches();
    tilejet::test::write_file(
        dir / "bad-zlib.png",
        tilejet::test::png_with_profile(
            swatches, tilejet::test::file_text(tilejet::test::kAdobeRgbProfile), true));
    REQUIRE_THAT(load_error(dir / "bad-zlib.png"), Contains("bad-zlib.png") && Contains("ICC"));
    // No profile at all: the pixels are taken as sRGB, unchanged, with no conversion needed.
    cv::Mat bgr;
    cv::cvtColor(swatches, bgr, cv::COLOR_RGB2BGR);
    cv::imwrite((dir / "plain.png").string(), bgr);
    REQUIRE(cv::norm(load_exemplar(dir / "plain.png", {}), swatches, cv::NORM_INF) == 0);
}
