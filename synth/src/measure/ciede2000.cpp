#include <cmath>
#include <numbers>

#include "tilejet/synth/colour_match.hpp"

namespace tilejet::synth {

// Straight from Sharma, Wu and Dalal, "The CIEDE2000 color-difference formula: implementation
// notes, supplementary test data, and mathematical observations" (2005), equations 1-17.
double ciede2000(const LabColour& x, const LabColour& y) {
    using std::atan2, std::cos, std::exp, std::fabs, std::pow, std::sin, std::sqrt;
    constexpr double pi = std::numbers::pi;
    auto deg = [](double r) { return r * 180 / pi; };
    auto rad = [](double d) { return d * pi / 180; };
    const double pow25_7 = 6103515625.0;  // 25^7

    const double c1 = sqrt(x.a * x.a + x.b * x.b), c2 = sqrt(y.a * y.a + y.b * y.b);
    const double c_bar7 = pow((c1 + c2) / 2, 7);
    const double g = 0.5 * (1 - sqrt(c_bar7 / (c_bar7 + pow25_7)));
    const double a1 = (1 + g) * x.a, a2 = (1 + g) * y.a;
    const double cp1 = sqrt(a1 * a1 + x.b * x.b), cp2 = sqrt(a2 * a2 + y.b * y.b);
    auto hue = [&](double b, double a) {
        if (a == 0 && b == 0) return 0.0;
        const double h = deg(atan2(b, a));
        return h < 0 ? h + 360 : h;
    };
    const double h1 = hue(x.b, a1), h2 = hue(y.b, a2);

    const double dl = y.L - x.L, dc = cp2 - cp1;
    double dh = 0;
    if (cp1 * cp2 != 0) {
        dh = h2 - h1;
        if (dh > 180) dh -= 360;
        if (dh < -180) dh += 360;
    }
    const double d_big_h = 2 * sqrt(cp1 * cp2) * sin(rad(dh / 2));

    const double l_bar = (x.L + y.L) / 2, cp_bar = (cp1 + cp2) / 2;
    double h_bar = h1 + h2;
    if (cp1 * cp2 != 0) {
        if (fabs(h1 - h2) <= 180)
            h_bar /= 2;
        else
            h_bar = h_bar < 360 ? (h_bar + 360) / 2 : (h_bar - 360) / 2;
    }
    const double t = 1 - 0.17 * cos(rad(h_bar - 30)) + 0.24 * cos(rad(2 * h_bar)) +
                     0.32 * cos(rad(3 * h_bar + 6)) - 0.20 * cos(rad(4 * h_bar - 63));
    const double d_theta = 30 * exp(-pow((h_bar - 275) / 25, 2));
    const double cp_bar7 = pow(cp_bar, 7);
    const double rc = 2 * sqrt(cp_bar7 / (cp_bar7 + pow25_7));
    const double l50 = (l_bar - 50) * (l_bar - 50);
    const double sl = 1 + 0.015 * l50 / sqrt(20 + l50);
    const double sc = 1 + 0.045 * cp_bar, sh = 1 + 0.015 * cp_bar * t;
    const double rt = -sin(rad(2 * d_theta)) * rc;
    const double tl = dl / sl, tc = dc / sc, th = d_big_h / sh;
    return sqrt(tl * tl + tc * tc + th * th + rt * tc * th);
}

}  // namespace tilejet::synth
