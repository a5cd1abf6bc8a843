#include "tilejet/colour/profile_report.hpp"

#include "icc_profile.hpp"
#include "tilejet/colour/ciede2000.hpp"
#include "tilejet/colour/cmyk_transform.hpp"
#include "tilejet/colour/statistics.hpp"

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
        errors.push_back(ciede2000({m.L, m.a, m.b}, {predicted.L, predicted.a, predicted.b}));
    }
    const Summary s = summarize(errors, 0.95);
    ProfileReport report;
    report.patches = s.count;
    report.mean = s.mean, report.p95 = s.percentile, report.max = s.max;
    return report;
}

}  // namespace tilejet::colour
