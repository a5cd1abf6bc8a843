#include "tilejet/colour/profile_report.hpp"

#include <algorithm>
#include <cmath>

#include "icc_profile.hpp"
#include "tilejet/colour/cmyk_transform.hpp"

namespace tilejet::colour {

ProfileReport check_profile(const std::filesystem::path& profile,
                            const std::vector<Measurement>& measurements) {
    detail::LcmsContext lcms;
    detail::IccProfile cmyk =
        detail::load_icc_profile(lcms, profile, "output profile", cmsSigCmykData);
    detail::Profile lab(cmsCreateLab4ProfileTHR(lcms.get(), nullptr));  // D50, as measured
    // Measurements are absolute (paper white included), so the prediction is too.
    detail::Transform predict(
        cmsCreateTransformTHR(lcms.get(), cmyk.handle.get(), TYPE_CMYK_DBL, lab.get(), TYPE_Lab_DBL,
                              INTENT_ABSOLUTE_COLORIMETRIC, cmsFLAGS_NOCACHE));
    if (!predict)
        throw ColourError("output profile '" + profile.string() +
                          "' cannot predict colours: " + lcms.take_error());
    std::vector<double> errors;
    errors.reserve(measurements.size());
    for (const Measurement& m : measurements) {
        const double ink[4] = {m.c, m.m, m.y, m.k};  // percent, as TYPE_CMYK_DBL takes
        cmsCIELab predicted;
        cmsDoTransform(predict.get(), ink, &predicted, 1);
        const cmsCIELab measured{m.L, m.a, m.b};
        errors.push_back(cmsCIE2000DeltaE(&measured, &predicted, 1, 1, 1));
    }
    ProfileReport report;
    report.patches = errors.size();
    if (errors.empty()) return report;
    double sum = 0;
    for (double e : errors)
        sum += e;
    report.mean = sum / double(errors.size());
    std::sort(errors.begin(), errors.end());
    report.p95 =
        errors[std::min(errors.size() - 1, size_t(std::ceil(0.95 * double(errors.size()))) - 1)];
    report.max = errors.back();
    return report;
}

}  // namespace tilejet::colour
