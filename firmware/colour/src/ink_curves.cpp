#include "ink_curves.hpp"

#include <toml++/toml.h>

#include <array>
#include <string>
#include <vector>

#include "tilejet/colour/cmyk_transform.hpp"

namespace tilejet::colour::detail {

namespace {

constexpr std::array<const char*, 4> kInks = {"cyan", "magenta", "yellow", "black"};
constexpr int kSamples = 4096;

std::string at(const std::filesystem::path& path, const toml::source_region& where) {
    return path.string() + ":" + std::to_string(where.begin.line);
}

// Piecewise-linear curve through `points` (percent in -> percent out), sampled for LittleCMS.
ToneCurve make_curve(LcmsContext& lcms, const std::vector<std::pair<double, double>>& points) {
    std::vector<cmsUInt16Number> table(kSamples);
    size_t seg = 0;
    for (int i = 0; i < kSamples; ++i) {
        const double x = 100.0 * i / (kSamples - 1);
        while (seg + 2 < points.size() && x > points[seg + 1].first)
            ++seg;
        const auto [x0, y0] = points[seg];
        const auto [x1, y1] = points[seg + 1];
        const double y = y0 + (y1 - y0) * (x - x0) / (x1 - x0);
        table[size_t(i)] = cmsUInt16Number(std::clamp(y / 100.0, 0.0, 1.0) * 65535.0 + 0.5);
    }
    return ToneCurve(cmsBuildTabulatedToneCurve16(lcms.get(), kSamples, table.data()));
}

}  // namespace

Profile load_ink_curves(LcmsContext& lcms, const std::filesystem::path& path) {
    toml::table root;
    try {
        root = toml::parse_file(path.string());
    } catch (const toml::parse_error& e) {
        throw ColourError("ink curves " + at(path, e.source()) + ": " +
                          std::string(e.description()));
    }
    for (const auto& [key, node] : root) {
        const std::string name(key.str());
        if (std::find_if(kInks.begin(), kInks.end(),
                         [&](const char* ink) { return name == ink; }) == kInks.end())
            throw ColourError("ink curves " + at(path, node.source()) + ": unknown section [" +
                              name + "]; inks are cyan, magenta, yellow, black");
    }

    std::array<ToneCurve, 4> curves;
    for (size_t i = 0; i < kInks.size(); ++i) {
        std::vector<std::pair<double, double>> points{{0, 0}, {100, 100}};
        if (const toml::table* ink = root[kInks[i]].as_table()) {
            const std::string section = std::string("[") + kInks[i] + "]";
            for (const auto& [key, node] : *ink)
                if (key.str() != "points")
                    throw ColourError("ink curves " + at(path, node.source()) + ": " + section +
                                      " unknown key '" + std::string(key.str()) + "'");
            const toml::array* list = (*ink)["points"].as_array();
            if (!list)
                throw ColourError("ink curves " + at(path, ink->source()) + ": " + section +
                                  " points: missing; expected [[in, out], ...] in percent");
            points.clear();
            for (const toml::node& item : *list) {
                const toml::array* pair = item.as_array();
                auto number = [&](size_t n) -> std::optional<double> {
                    if (!pair || pair->size() != 2) return std::nullopt;
                    return (*pair)[n].value<double>();
                };
                const auto in = number(0), out = number(1);
                if (!in || !out || *in < 0 || *in > 100 || *out < 0 || *out > 100)
                    throw ColourError("ink curves " + at(path, item.source()) + ": " + section +
                                      " points: each point is [in, out] with both in 0..100");
                if (!points.empty() && *in <= points.back().first)
                    throw ColourError("ink curves " + at(path, item.source()) + ": " + section +
                                      " points: inputs must ascend");
                points.emplace_back(*in, *out);
            }
            if (points.size() < 2 || points.front().first != 0 || points.back().first != 100)
                throw ColourError("ink curves " + at(path, list->source()) + ": " + section +
                                  " points: need at least [0, x] and [100, y]");
        }
        curves[i] = make_curve(lcms, points);
        if (!curves[i])
            throw ColourError("ink curves '" + path.string() + "': LittleCMS refused a curve");
    }
    cmsToneCurve* raw[4] = {curves[0].get(), curves[1].get(), curves[2].get(), curves[3].get()};
    Profile link(cmsCreateLinearizationDeviceLinkTHR(lcms.get(), cmsSigCmykData, raw));
    if (!link) throw ColourError("ink curves '" + path.string() + "': " + lcms.take_error());
    return link;
}

}  // namespace tilejet::colour::detail
