// tilejet analyze: the lattice of an exemplar, as one JSON object; optionally its
// fractional-Fourier regular-structure mask as an image.

#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

#include "commands.hpp"
#include "tilejet/colour/exemplar_profile.hpp"
#include "tilejet/synth/fourier_mask.hpp"
#include "tilejet/synth/lattice.hpp"

namespace tilejet::cli {

namespace {

void write_grey_png(const cv::Mat& grey, const std::filesystem::path& path) {
    if (path.extension() != ".png")
        throw std::runtime_error("--mask '" + path.string() + "': use a .png file name");
    bool ok = false;
    try {
        ok = cv::imwrite(path.string(), grey);
    } catch (const cv::Exception& e) {
        throw std::runtime_error("cannot write '" + path.string() + "': " + e.what());
    }
    if (!ok) throw std::runtime_error("cannot write '" + path.string() + "'");
}

}  // namespace

void add_analyze_commands(CLI::App& app) {
    auto path = std::make_shared<std::string>(), mask = std::make_shared<std::string>();
    CLI::App* analyze = app.add_subcommand(
        "analyze", "detect an exemplar's lattice (brick, mosaic, textile) and its regularity");
    analyze->add_option("EXEMPLAR", *path, "PNG, JPEG or TIFF exemplar")->required();
    analyze->add_option("--mask", *mask,
                        "also write the fractional-Fourier regular-structure mask (8-bit grey "
                        "PNG, the exemplar's size)");
    analyze->callback([path, mask] {
        const cv::Mat exemplar = colour::load_exemplar(*path);
        if (!mask->empty()) {
            const cv::Mat grey = synth::find_fourier_mask(exemplar).evaluate_8bit(exemplar.size());
            write_grey_png(grey, *mask);
        }
        const synth::Lattice l = synth::detect_lattice(exemplar);
        nlohmann::ordered_json j;
        j["v1"] = {l.v1.x, l.v1.y};
        j["v2"] = {l.v2.x, l.v2.y};
        j["score"] = l.score;
        j["kind"] = synth::lattice_kind_name(l.kind);
        if (l.appearance_regularity) j["A"] = *l.appearance_regularity;
        if (l.geometry_regularity) j["G"] = *l.geometry_regularity;
        if (l.kind == synth::LatticeKind::Courses) {
            j["pitch"] = l.pitch;
            j["note"] = "courses: v1 runs along them, v2 is the pitch across them in whole pixels";
        }
        if (l.kind == synth::LatticeKind::Stochastic)
            j["note"] = "no lattice found: stochastic texture, unit vectors reported";
        std::printf("%s\n", j.dump().c_str());
    });
}

}  // namespace tilejet::cli
