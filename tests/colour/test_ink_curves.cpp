#include <catch2/catch.hpp>

#include "../synth/fixtures.hpp"
#include "colour_fixtures.hpp"
#include "tilejet/colour/cmyk_transform.hpp"

using namespace tilejet;
using Catch::Matchers::Contains;

namespace {

colour::ColourSettings with_curves(const std::filesystem::path& curves) {
    colour::ColourSettings s;
    s.output_profile = test::test_cmyk_profile();
    s.ink_limit_percent = 400;
    s.ink_curves = curves;
    return s;
}

cv::Mat some_colours() {
    cv::Mat rgb(1, 6, CV_8UC3);
    const uint8_t colours[6][3] = {{20, 120, 200},  {90, 160, 60}, {200, 40, 40},
                                   {128, 128, 128}, {30, 30, 30},  {240, 220, 180}};
    for (int i = 0; i < 6; ++i)
        rgb.at<cv::Vec3b>(0, i) = {colours[i][0], colours[i][1], colours[i][2]};
    return rgb;
}

}  // namespace

TEST_CASE("linearization curves change the inks they name and only those", "[colour][curves]") {
    test::TempDir dir;
    test::write_file(dir / "identity.toml", "[cyan]\npoints = [[0, 0], [100, 100]]\n");
    test::write_file(dir / "less-cyan.toml", "[cyan]\npoints = [[0, 0], [100, 50]]\n");
    colour::ColourSettings plain = with_curves({});
    const cv::Mat rgb = some_colours();
    const cv::Mat base = colour::CmykTransform(plain).to_cmyk(rgb);
    const cv::Mat same = colour::CmykTransform(with_curves(dir / "identity.toml")).to_cmyk(rgb);
    const cv::Mat less = colour::CmykTransform(with_curves(dir / "less-cyan.toml")).to_cmyk(rgb);
    for (int i = 0; i < rgb.cols; ++i) {
        const cv::Vec4b b = base.at<cv::Vec4b>(0, i), s = same.at<cv::Vec4b>(0, i),
                        l = less.at<cv::Vec4b>(0, i);
        for (int c = 0; c < 4; ++c)
            REQUIRE(std::abs(int(s[c]) - int(b[c])) <= 1);
        REQUIRE(std::abs(int(l[0]) - int(b[0]) / 2) <= 2);
        for (int c = 1; c < 4; ++c)
            REQUIRE(std::abs(int(l[c]) - int(b[c])) <= 1);
    }
}

TEST_CASE("broken curve tables fail naming the file, section and key", "[colour][curves]") {
    test::TempDir dir;
    auto error = [&](const std::string& text) {
        test::write_file(dir / "curves.toml", text);
        try {
            colour::CmykTransform t(with_curves(dir / "curves.toml"));
        } catch (const colour::ColourError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    REQUIRE_THAT(error("[cyan\npoints = 1"), Contains("curves.toml:1"));
    REQUIRE_THAT(error("[orange]\npoints = [[0,0],[100,100]]\n"), Contains("[orange]"));
    REQUIRE_THAT(error("[cyan]\npoint = [[0,0],[100,100]]\n"),
                 Contains("[cyan]") && Contains("point"));
    REQUIRE_THAT(error("[cyan]\npoints = [[0,0],[120,100]]\n"),
                 Contains("curves.toml:2") && Contains("0..100"));
    REQUIRE_THAT(error("[black]\npoints = [[0,0],[60,50],[40,70],[100,100]]\n"),
                 Contains("ascend"));
    REQUIRE_THAT(error("[yellow]\npoints = [[10,0],[100,100]]\n"), Contains("[0, x]"));
}
