#include "tilejet/colour/exemplar_profile.hpp"

#include <opencv2/imgproc.hpp>

#include "icc_profile.hpp"
#include "lcms_context.hpp"
#include "tilejet/colour/cmyk_transform.hpp"
#include "tilejet/synth/error.hpp"
#include "tilejet/synth/exemplar.hpp"

namespace tilejet::colour {

using namespace detail;

void exemplar_to_srgb(cv::Mat& rgb, const std::vector<uint8_t>& icc, const std::string& name) {
    LcmsContext lcms;
    // Grey scans keep their grey profile; anything else must describe RGB (parse_icc_profile
    // refuses a CMYK photo by name).
    const bool grey = icc_data_space(icc) == uint32_t(cmsSigGrayData);
    IccProfile source;
    try {
        source = parse_icc_profile(lcms, icc, name, "ICC profile embedded in exemplar",
                                   grey ? cmsSigGrayData : cmsSigRgbData);
    } catch (const ColourError& e) {
        throw synth::SynthError(std::string(e.what()) + "; re-save the exemplar as sRGB");
    }
    Profile srgb(cmsCreate_sRGBProfileTHR(lcms.get()));
    Transform transform(cmsCreateTransformTHR(
        lcms.get(), source.handle.get(), grey ? TYPE_GRAY_8 : TYPE_RGB_8, srgb.get(), TYPE_RGB_8,
        INTENT_RELATIVE_COLORIMETRIC, cmsFLAGS_BLACKPOINTCOMPENSATION | cmsFLAGS_NOCACHE));
    if (!transform)
        throw synth::SynthError(
            "exemplar '" + name +
            "': its embedded profile cannot be converted to sRGB: " + lcms.take_error());
    cv::Mat input = rgb;
    if (grey) cv::extractChannel(rgb, input, 0);
    cv::Mat out(rgb.size(), CV_8UC3);
    for (int r = 0; r < rgb.rows; ++r)
        cmsDoTransform(transform.get(), input.ptr(r), out.ptr(r), cmsUInt32Number(rgb.cols));
    rgb = out;
}

cv::Mat load_exemplar(const std::filesystem::path& path) {
    return synth::load_exemplar(path, exemplar_to_srgb);
}

}  // namespace tilejet::colour
