// Exemplars that embed an ICC profile are converted to sRGB on intake, by the colour module's
// LittleCMS wrapper; a profile that cannot describe the pixels is refused naming the file.

#include <lcms2.h>

#include <catch2/catch.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "../synth/fixtures.hpp"
#include "../synth/profile_files.hpp"
#include "tilejet/colour/exemplar_profile.hpp"
#include "tilejet/synth/error.hpp"

using Catch::Matchers::Contains;
using tilejet::test::file_text;
using tilejet::test::kAdobeRgbProfile;
using tilejet::test::saturated_swatches;
using tilejet::test::TempDir;
using tilejet::test::write_file;

namespace {

// What the exemplar should become: `rgb` taken from profile `from` (RGB or grey) to sRGB by
// LittleCMS called directly, an oracle independent of the colour module's wrapper.
cv::Mat profile_to_srgb(const cv::Mat& rgb, const char* from, bool grey = false) {
    cmsHPROFILE source = cmsOpenProfileFromFile(from, "r");
    cmsHPROFILE srgb = cmsCreate_sRGBProfile();
    cmsHTRANSFORM t =
        cmsCreateTransform(source, grey ? TYPE_GRAY_8 : TYPE_RGB_8, srgb, TYPE_RGB_8,
                           INTENT_RELATIVE_COLORIMETRIC, cmsFLAGS_BLACKPOINTCOMPENSATION);
    cv::Mat input = rgb;
    if (grey) cv::extractChannel(rgb, input, 0);
    cv::Mat out(rgb.size(), CV_8UC3);
    for (int r = 0; r < rgb.rows; ++r)
        cmsDoTransform(t, input.ptr(r), out.ptr(r), cmsUInt32Number(rgb.cols));
    cmsDeleteTransform(t);
    cmsCloseProfile(srgb);
    cmsCloseProfile(source);
    return out;
}

std::string load_error(const std::filesystem::path& path) {
    try {
        tilejet::colour::load_exemplar(path);
    } catch (const tilejet::synth::SynthError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("an exemplar with an embedded Adobe RGB profile is converted to sRGB",
          "[exemplar][icc]") {
    TempDir dir;
    const std::string icc = file_text(kAdobeRgbProfile);
    REQUIRE(icc.size() > 128);
    const cv::Mat swatches = saturated_swatches();

    write_file(dir / "adobe.png", tilejet::test::png_with_profile(swatches, icc));
    const cv::Mat png = tilejet::colour::load_exemplar(dir / "adobe.png");
    REQUIRE(cv::norm(png, profile_to_srgb(swatches, kAdobeRgbProfile), cv::NORM_INF) == 0);
    REQUIRE(cv::norm(png, swatches, cv::NORM_INF) > 10);  // Adobe RGB greens are not sRGB greens

    const std::string jpg = tilejet::test::jpeg_with_profile(swatches, icc);
    write_file(dir / "adobe.jpg", jpg);
    cv::Mat decoded;
    cv::cvtColor(cv::imdecode(std::vector<uchar>(jpg.begin(), jpg.end()), cv::IMREAD_COLOR),
                 decoded, cv::COLOR_BGR2RGB);
    REQUIRE(cv::norm(tilejet::colour::load_exemplar(dir / "adobe.jpg"),
                     profile_to_srgb(decoded, kAdobeRgbProfile), cv::NORM_INF) == 0);
}

TEST_CASE("a grey exemplar with a grey profile is converted through it", "[exemplar][icc]") {
    const char* kGrey = "/usr/share/color/icc/Gray.icc";
    cv::Mat ramp(32, 32, CV_8UC3);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x)
            ramp.at<cv::Vec3b>(y, x) = cv::Vec3b::all(uint8_t(x * 8));
    TempDir dir;
    write_file(dir / "grey.png", tilejet::test::png_with_profile(ramp, file_text(kGrey)));
    const cv::Mat loaded = tilejet::colour::load_exemplar(dir / "grey.png");
    REQUIRE(cv::norm(loaded, profile_to_srgb(ramp, kGrey, true), cv::NORM_INF) == 0);
}

TEST_CASE("an embedded profile that cannot describe the pixels is refused naming the file",
          "[exemplar][icc]") {
    TempDir dir;
    const cv::Mat swatches = saturated_swatches();
    write_file(dir / "not-icc.png",
               tilejet::test::png_with_profile(swatches, std::string(300, 'x')));
    REQUIRE_THAT(load_error(dir / "not-icc.png"), Contains("not-icc.png") && Contains("ICC"));

    // A CMYK photo: its profile is CMYK, the pixels decoded as RGB.
    write_file(dir / "cmyk.png",
               tilejet::test::png_with_profile(swatches, file_text(TILEJET_TEST_CMYK_PROFILE)));
    REQUIRE_THAT(load_error(dir / "cmyk.png"), Contains("cmyk.png") && Contains("CMYK"));

    // A profile whose header promises more bytes than the chunk holds.
    std::string cut = file_text(kAdobeRgbProfile);
    cut.resize(200);
    write_file(dir / "cut.png", tilejet::test::png_with_profile(swatches, cut));
    REQUIRE_THAT(load_error(dir / "cut.png"), Contains("cut.png") && Contains("truncated"));

    // No profile at all: the pixels are taken as sRGB, unchanged.
    cv::Mat bgr;
    cv::cvtColor(swatches, bgr, cv::COLOR_RGB2BGR);
    cv::imwrite((dir / "plain.png").string(), bgr);
    REQUIRE(cv::norm(tilejet::colour::load_exemplar(dir / "plain.png"), swatches, cv::NORM_INF) ==
            0);
}
