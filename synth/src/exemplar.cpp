#include "tilejet/synth/exemplar.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "embedded_profile.hpp"
#include "tilejet/synth/error.hpp"

namespace tilejet::synth {

namespace {

// The exemplar limits on a size, in memory or as a file's header gives it.
void check_size(cv::Size size, const std::string& name) {
    if (size.width < kMinExemplarSide || size.height < kMinExemplarSide)
        throw SynthError("exemplar '" + name + "' is " + std::to_string(size.width) + "x" +
                         std::to_string(size.height) + " px; a texture needs at least " +
                         std::to_string(kMinExemplarSide) + "x" + std::to_string(kMinExemplarSide) +
                         " px");
    if (int64_t(size.width) * size.height > kMaxExemplarPixels)
        throw SynthError("exemplar '" + name + "' is " + std::to_string(size.width) + "x" +
                         std::to_string(size.height) + " px; texture maps take exemplars up to " +
                         std::to_string(kMaxExemplarPixels >> 20) +
                         " Mpx (e.g. 8192x8192): crop or scale it first");
}

}  // namespace

void check_exemplar(const cv::Mat& rgb, const std::string& name) {
    if (rgb.empty()) throw SynthError("exemplar '" + name + "' is empty");
    if (rgb.type() != CV_8UC3)
        throw SynthError("exemplar '" + name + "' is not 8-bit RGB in memory");
    check_size(rgb.size(), name);
}

cv::Mat load_exemplar(const std::filesystem::path& path, const EmbeddedProfileConversion& to_srgb) {
    const std::string name = path.string();
    {
        std::ifstream probe(path, std::ios::binary);
        if (!probe)
            throw SynthError("cannot read exemplar '" + name + "': " + std::strerror(errno));
        if (probe.peek() == std::ifstream::traits_type::eof())
            throw SynthError("exemplar '" + name + "' is an empty file");
    }
    // Too large is refused from the header, before the pixels are decoded (and allocated).
    if (const auto header = read_image_size(path);
        header && int64_t(header->width) * header->height > kMaxExemplarPixels)
        check_size(*header, name);
    // IMREAD_COLOR turns grey and 16-bit images into 8-bit three-channel ones and drops alpha.
    cv::Mat bgr;
    try {
        bgr = cv::imread(name, cv::IMREAD_COLOR);
    } catch (const cv::Exception& e) {
        throw SynthError("cannot decode exemplar '" + name + "': " + e.what());
    }
    if (bgr.empty())
        throw SynthError("cannot decode exemplar '" + name +
                         "': not a PNG, JPEG or TIFF image, damaged, or too large to decode");
    cv::Mat rgb;
    cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
    check_exemplar(rgb, name);
    // Texture maps are sRGB: a photo in Adobe RGB or a camera profile is converted on intake,
    // so the colour module's default source profile is right for every map.
    const std::vector<uint8_t> icc = detail::read_embedded_profile(path);
    if (!icc.empty()) {
        if (!to_srgb)
            throw SynthError("exemplar '" + name +
                             "' embeds an ICC profile and nothing was given to convert it to sRGB");
        to_srgb(rgb, icc, name);
    }
    return rgb;
}

}  // namespace tilejet::synth
