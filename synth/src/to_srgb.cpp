#include "to_srgb.hpp"

#include <lcms2.h>

#include <memory>
#include <opencv2/imgproc.hpp>

#include "tilejet/synth/error.hpp"

namespace tilejet::synth::detail {

namespace {

struct ProfileCloser {
    void operator()(void* p) const { cmsCloseProfile(p); }
};
struct TransformDeleter {
    void operator()(void* t) const { cmsDeleteTransform(t); }
};

}  // namespace

void convert_to_srgb(cv::Mat& rgb, const std::vector<uint8_t>& icc, const std::string& name) {
    std::unique_ptr<void, ProfileCloser> source(
        cmsOpenProfileFromMem(icc.data(), cmsUInt32Number(icc.size())));
    if (!source)
        throw SynthError("exemplar '" + name +
                         "' embeds an ICC profile LittleCMS cannot read; "
                         "re-save it as sRGB");
    // Read as a plain number from the header: a crafted file can hold a value outside
    // LittleCMS's enum, and loading that as the enum is undefined behaviour.
    const uint32_t space = icc.size() >= 20 ? uint32_t(icc[16]) << 24 | uint32_t(icc[17]) << 16 |
                                                  uint32_t(icc[18]) << 8 | icc[19]
                                            : 0;
    if (space != uint32_t(cmsSigRgbData) && space != uint32_t(cmsSigGrayData))
        throw SynthError("exemplar '" + name +
                         "' embeds a profile that is neither RGB nor grey "
                         "(a CMYK photo?); re-save it as RGB");
    std::unique_ptr<void, ProfileCloser> srgb(cmsCreate_sRGBProfile());
    const bool grey = space == uint32_t(cmsSigGrayData);
    std::unique_ptr<void, TransformDeleter> transform(cmsCreateTransform(
        source.get(), grey ? TYPE_GRAY_8 : TYPE_RGB_8, srgb.get(), TYPE_RGB_8,
        INTENT_RELATIVE_COLORIMETRIC, cmsFLAGS_BLACKPOINTCOMPENSATION | cmsFLAGS_NOCACHE));
    if (!transform)
        throw SynthError("exemplar '" + name +
                         "': its embedded profile cannot be converted to sRGB");
    cv::Mat input = rgb;
    if (grey) cv::extractChannel(rgb, input, 0);
    cv::Mat out(rgb.size(), CV_8UC3);
    for (int r = 0; r < rgb.rows; ++r)
        cmsDoTransform(transform.get(), input.ptr(r), out.ptr(r), cmsUInt32Number(rgb.cols));
    rgb = out;
}

}  // namespace tilejet::synth::detail
