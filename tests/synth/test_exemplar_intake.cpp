// Exemplars as engineers bring them: odd formats work, broken ones fail with a clear message.

#include <lcms2.h>
#include <zlib.h>

#include <catch2/catch.hpp>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "fixtures.hpp"
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
        load_exemplar(path);
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
    const cv::Mat loaded = load_exemplar(dir / "grey.png");
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
    const cv::Mat loaded = load_exemplar(dir / "deep.png");
    REQUIRE(loaded.type() == CV_8UC3);
    REQUIRE(cv::norm(loaded, demo_exemplar(), cv::NORM_INF) <= 1);
}

TEST_CASE("a huge exemplar is refused with its size, without a crash", "[exemplar][slow]") {
    TempDir dir;
    {
        const cv::Mat huge(20000, 20000, CV_8UC3, cv::Scalar(90, 90, 90));
        REQUIRE(cv::imwrite((dir / "huge.png").string(), huge, {cv::IMWRITE_PNG_COMPRESSION, 1}));
    }
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

namespace {

const char* kAdobeRgb = "/usr/share/color/icc/compatibleWithAdobeRGB1998.icc";

std::string file_text(const char* path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void put_be32(std::string& s, uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8)
        s += char((v >> shift) & 0xFF);
}

// A PNG of `rgb` with `icc` in an iCCP chunk right after IHDR, as image editors write it.
std::string png_with_profile(const cv::Mat& rgb, const std::string& icc, bool break_zlib = false) {
    cv::Mat bgr;
    cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
    std::vector<uchar> png;
    cv::imencode(".png", bgr, png);
    uLongf len = compressBound(uLong(icc.size()));
    std::string z(len, '\0');
    compress2(reinterpret_cast<Bytef*>(z.data()), &len, reinterpret_cast<const Bytef*>(icc.data()),
              uLong(icc.size()), 9);
    z.resize(len);
    if (break_zlib) z[z.size() / 2] = char(z[z.size() / 2] ^ 0x55), z.resize(z.size() - 4);
    const std::string body = std::string("iCCP") + "Adobe RGB" + '\0' + '\0' + z;
    std::string chunk;
    put_be32(chunk, uint32_t(body.size() - 4));
    chunk += body;
    put_be32(chunk,
             uint32_t(crc32(0, reinterpret_cast<const Bytef*>(body.data()), uInt(body.size()))));
    std::string out(png.begin(), png.end());
    out.insert(33, chunk);  // 8-byte signature + IHDR (4 + 4 + 13 + 4)
    return out;
}

std::string jpeg_with_profile(const cv::Mat& rgb, const std::string& icc) {
    cv::Mat bgr;
    cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
    std::vector<uchar> jpg;
    cv::imencode(".jpg", bgr, jpg, {cv::IMWRITE_JPEG_QUALITY, 95});
    std::string segment = "\xFF\xE2";
    const size_t length = 2 + 12 + 2 + icc.size();
    segment += char(length >> 8), segment += char(length & 0xFF);
    segment += std::string("ICC_PROFILE") + '\0' + char(1) + char(1) + icc;
    std::string out(jpg.begin(), jpg.end());
    out.insert(2, segment);
    return out;
}

// What the exemplar should become: the decoded pixels taken from Adobe RGB to sRGB.
cv::Mat adobe_to_srgb(const cv::Mat& rgb) {
    cmsHPROFILE adobe = cmsOpenProfileFromFile(kAdobeRgb, "r");
    cmsHPROFILE srgb = cmsCreate_sRGBProfile();
    cmsHTRANSFORM t =
        cmsCreateTransform(adobe, TYPE_RGB_8, srgb, TYPE_RGB_8, INTENT_RELATIVE_COLORIMETRIC,
                           cmsFLAGS_BLACKPOINTCOMPENSATION);
    cv::Mat out(rgb.size(), CV_8UC3);
    for (int r = 0; r < rgb.rows; ++r)
        cmsDoTransform(t, rgb.ptr(r), out.ptr(r), cmsUInt32Number(rgb.cols));
    cmsDeleteTransform(t);
    cmsCloseProfile(srgb);
    cmsCloseProfile(adobe);
    return out;
}

cv::Mat saturated_swatches() {
    cv::Mat rgb(32, 32, CV_8UC3);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x)
            rgb.at<cv::Vec3b>(y, x) = {uint8_t(x * 8), uint8_t(200 - y * 4), uint8_t(40 + x * 4)};
    return rgb;
}

}  // namespace

TEST_CASE("an exemplar with an embedded Adobe RGB profile is converted to sRGB",
          "[exemplar][icc]") {
    TempDir dir;
    const std::string icc = file_text(kAdobeRgb);
    REQUIRE(icc.size() > 128);
    const cv::Mat swatches = saturated_swatches();

    tilejet::test::write_file(dir / "adobe.png", png_with_profile(swatches, icc));
    const cv::Mat png = load_exemplar(dir / "adobe.png");
    REQUIRE(cv::norm(png, adobe_to_srgb(swatches), cv::NORM_INF) == 0);
    REQUIRE(cv::norm(png, swatches, cv::NORM_INF) > 10);  // Adobe RGB greens are not sRGB greens

    const std::string jpg = jpeg_with_profile(swatches, icc);
    tilejet::test::write_file(dir / "adobe.jpg", jpg);
    cv::Mat decoded;
    cv::cvtColor(cv::imdecode(std::vector<uchar>(jpg.begin(), jpg.end()), cv::IMREAD_COLOR),
                 decoded, cv::COLOR_BGR2RGB);
    REQUIRE(cv::norm(load_exemplar(dir / "adobe.jpg"), adobe_to_srgb(decoded), cv::NORM_INF) == 0);
}

TEST_CASE("a damaged embedded profile is refused naming the file", "[exemplar][icc]") {
    TempDir dir;
    const cv::Mat swatches = saturated_swatches();
    tilejet::test::write_file(dir / "bad-zlib.png",
                              png_with_profile(swatches, file_text(kAdobeRgb), true));
    REQUIRE_THAT(load_error(dir / "bad-zlib.png"), Contains("bad-zlib.png") && Contains("ICC"));
    tilejet::test::write_file(dir / "not-icc.png",
                              png_with_profile(swatches, std::string(300, 'x')));
    REQUIRE_THAT(load_error(dir / "not-icc.png"), Contains("not-icc.png") && Contains("ICC"));
    // No profile at all: the pixels are taken as sRGB, unchanged.
    cv::Mat bgr;
    cv::cvtColor(swatches, bgr, cv::COLOR_RGB2BGR);
    cv::imwrite((dir / "plain.png").string(), bgr);
    REQUIRE(cv::norm(load_exemplar(dir / "plain.png"), swatches, cv::NORM_INF) == 0);
}
