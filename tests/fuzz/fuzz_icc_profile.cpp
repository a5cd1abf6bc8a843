// libFuzzer: ICC profile intake for the line's output profile, and LittleCMS on what we accept.
#include <cstdint>
#include <vector>

#include "icc_profile.hpp"
#include "tilejet/colour/cmyk_transform.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace tilejet::colour;
    try {
        detail::LcmsContext lcms;
        detail::IccProfile p =
            detail::parse_icc_profile(lcms, std::vector<uint8_t>(data, data + size), "fuzz.icc",
                                      "output profile", cmsSigCmykData);
        detail::Profile srgb(cmsCreate_sRGBProfileTHR(lcms.get()));
        detail::Transform t(cmsCreateTransformTHR(lcms.get(), srgb.get(), TYPE_RGB_8,
                                                  p.handle.get(), TYPE_CMYK_8, INTENT_PERCEPTUAL,
                                                  cmsFLAGS_NOCACHE));
        if (t) {
            const uint8_t rgb[12] = {0, 0, 0, 255, 255, 255, 200, 30, 60, 10, 220, 90};
            uint8_t cmyk[16];
            cmsDoTransform(t.get(), rgb, cmyk, 4);
        }
    } catch (const ColourError&) {
    }
    return 0;
}
