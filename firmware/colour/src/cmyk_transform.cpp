#include "tilejet/colour/cmyk_transform.hpp"

#include <openssl/evp.h>

#include <cmath>
#include <fstream>
#include <iterator>

#include "icc_profile.hpp"
#include "ink_curves.hpp"
#include "ink_limit.hpp"
#include "lcms_context.hpp"

namespace tilejet::colour {

using namespace detail;

struct CmykTransform::Handles {
    LcmsContext lcms;
    Transform forward, proof;
    int ink_limit = 4 * 255;
};

namespace {

cmsUInt32Number lcms_intent(Intent intent) {
    switch (intent) {
        case Intent::Perceptual:
            return INTENT_PERCEPTUAL;
        case Intent::RelativeColorimetric:
            return INTENT_RELATIVE_COLORIMETRIC;
        case Intent::Saturation:
            return INTENT_SATURATION;
        case Intent::AbsoluteColorimetric:
            return INTENT_ABSOLUTE_COLORIMETRIC;
    }
    return INTENT_PERCEPTUAL;
}

std::vector<uint8_t> file_bytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string sha256_hex(const std::vector<std::vector<uint8_t>>& parts) {
    std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(), EVP_MD_CTX_free);
    EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr);
    for (const auto& p : parts) {
        const uint64_t n = p.size();
        EVP_DigestUpdate(ctx.get(), &n, sizeof n);
        EVP_DigestUpdate(ctx.get(), p.data(), p.size());
    }
    unsigned char md[32];
    unsigned int len = 0;
    EVP_DigestFinal_ex(ctx.get(), md, &len);
    static const char digits[] = "0123456789abcdef";
    std::string hex;
    for (unsigned i = 0; i < len; ++i)
        hex += digits[md[i] >> 4], hex += digits[md[i] & 15];
    return hex;
}

}  // namespace

CmykTransform::CmykTransform(const ColourSettings& settings)
    : settings_(settings), handles_(std::make_unique<Handles>()) {
    if (!(settings.ink_limit_percent >= 0 && settings.ink_limit_percent <= 400))
        throw ColourError("ink limit " + std::to_string(settings.ink_limit_percent) +
                          " % is outside 0..400");
    if (settings.output_profile.empty()) throw ColourError("no output (CMYK) profile given");
    LcmsContext& lcms = handles_->lcms;

    IccProfile output =
        load_icc_profile(lcms, settings.output_profile, "output profile", cmsSigCmykData);
    output_icc_ = output.bytes;
    Profile source;
    std::vector<uint8_t> source_bytes = {'s', 'R', 'G', 'B'};
    if (settings.source_profile.empty()) {
        source.reset(cmsCreate_sRGBProfileTHR(lcms.get()));
    } else {
        IccProfile p =
            load_icc_profile(lcms, settings.source_profile, "source profile", cmsSigRgbData);
        source_bytes = std::move(p.bytes);
        source = std::move(p.handle);
    }

    std::vector<cmsHPROFILE> chain = {source.get(), output.handle.get()};
    Profile curves;
    if (!settings.ink_curves.empty()) {
        curves = load_ink_curves(lcms, settings.ink_curves);
        chain.push_back(curves.get());
    }
    handles_->ink_limit = detail::ink_limit_value(settings.ink_limit_percent);
    Profile limiter;
    if (handles_->ink_limit < 4 * 255) {
        limiter.reset(cmsCreateInkLimitingDeviceLinkTHR(lcms.get(), cmsSigCmykData,
                                                        settings.ink_limit_percent));
        if (!limiter)
            throw ColourError("LittleCMS could not build the ink limit: " + lcms.take_error());
        chain.push_back(limiter.get());
    }

    // NOCACHE: the one-pixel cache is shared state; without it one transform serves every
    // render thread at once.
    cmsUInt32Number flags = cmsFLAGS_NOCACHE;
    if (settings.black_point_compensation) flags |= cmsFLAGS_BLACKPOINTCOMPENSATION;
    const cmsUInt32Number intent = lcms_intent(settings.intent);
    handles_->forward.reset(
        cmsCreateMultiprofileTransformTHR(lcms.get(), chain.data(), cmsUInt32Number(chain.size()),
                                          TYPE_RGB_8, TYPE_CMYK_8, intent, flags));
    if (!handles_->forward)
        throw ColourError("cannot make a transform from " +
                          (settings.source_profile.empty() ? std::string("sRGB")
                                                           : settings.source_profile.string()) +
                          " to '" + settings.output_profile.string() + "' (" +
                          std::string(intent_name(settings.intent)) + "): " + lcms.take_error());

    // The soft proof shows what the line lays down, so it is colorimetric, on a screen's white.
    Profile srgb(cmsCreate_sRGBProfileTHR(lcms.get()));
    handles_->proof.reset(cmsCreateTransformTHR(
        lcms.get(), output.handle.get(), TYPE_CMYK_8, srgb.get(), TYPE_RGB_8,
        INTENT_RELATIVE_COLORIMETRIC, cmsFLAGS_NOCACHE | cmsFLAGS_BLACKPOINTCOMPENSATION));
    if (!handles_->proof)
        throw ColourError("cannot make the soft-proof transform: " + lcms.take_error());

    const std::string setting_text = std::string(intent_name(settings.intent)) +
                                     (settings.black_point_compensation ? " bpc " : " nobpc ") +
                                     std::to_string(handles_->ink_limit);
    key_ = sha256_hex(
        {source_bytes, output_icc_,
         settings.ink_curves.empty() ? std::vector<uint8_t>{} : file_bytes(settings.ink_curves),
         std::vector<uint8_t>(setting_text.begin(), setting_text.end())});
}

CmykTransform::~CmykTransform() = default;

int CmykTransform::ink_limit_value() const {
    return handles_->ink_limit;
}

void CmykTransform::convert(const uint8_t* rgb, uint8_t* cmyk, size_t pixels) const {
    // LittleCMS takes 32-bit pixel counts.
    constexpr size_t kChunk = size_t(1) << 24;
    for (size_t done = 0; done < pixels; done += kChunk) {
        const size_t n = std::min(kChunk, pixels - done);
        cmsDoTransform(handles_->forward.get(), rgb + 3 * done, cmyk + 4 * done,
                       cmsUInt32Number(n));
    }
    enforce_ink_limit(cmyk, pixels, handles_->ink_limit);
}

cv::Mat CmykTransform::to_cmyk(const cv::Mat& rgb) const {
    CV_Assert(rgb.type() == CV_8UC3);
    cv::Mat cmyk(rgb.size(), CV_8UC4);
    for (int r = 0; r < rgb.rows; ++r)
        convert(rgb.ptr(r), cmyk.ptr(r), size_t(rgb.cols));
    return cmyk;
}

cv::Mat CmykTransform::proof(const cv::Mat& cmyk) const {
    CV_Assert(cmyk.type() == CV_8UC4);
    cv::Mat rgb(cmyk.size(), CV_8UC3);
    for (int r = 0; r < cmyk.rows; ++r)
        cmsDoTransform(handles_->proof.get(), cmyk.ptr(r), rgb.ptr(r), cmsUInt32Number(cmyk.cols));
    return rgb;
}

}  // namespace tilejet::colour
