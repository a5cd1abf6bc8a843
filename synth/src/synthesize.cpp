#include "tilejet/synth/synthesize.hpp"

#include <string>

#include "tilejet/config/enum_names.hpp"
#include "tilejet/synth/error.hpp"
#include "tilejet/synth/internal/enm.hpp"
#include "tilejet/synth/internal/rsgf.hpp"
#include "tilejet/synth/lattice.hpp"
#include "tilejet/synth/quilt.hpp"

namespace tilejet::synth {

namespace {

constexpr config::EnumNames kMethods{std::array<std::pair<SynthMethod, std::string_view>, 3>{{
    {SynthMethod::Quilt, "quilt"},
    {SynthMethod::Rsgf, "rsgf"},
    {SynthMethod::Enm, "enm"},
}}};

}  // namespace

std::string_view synth_method_name(SynthMethod method) {
    return kMethods.name(method);
}

SynthMethod parse_synth_method(std::string_view text, std::string_view option) {
    if (const auto method = kMethods.parse(text)) return *method;
    throw SynthError(std::string(option) + " '" + std::string(text) + "': expected " +
                     kMethods.choices());
}

cv::Mat synthesize(const cv::Mat& exemplar, SynthMethod method, cv::Size size, uint64_t seed) {
    if (size.width < 1 || size.height < 1 || size.width > kMaxSynthSide ||
        size.height > kMaxSynthSide)
        throw SynthError("--size " + std::to_string(size.width) + "x" +
                         std::to_string(size.height) + ": each side must be between 1 and " +
                         std::to_string(kMaxSynthSide) + " px");
    switch (method) {
        case SynthMethod::Quilt:
            return quilt_image(exemplar, size, seed);
        case SynthMethod::Rsgf:
            return synthesize_rsgf(exemplar, detect_lattice(exemplar), size, seed);
        case SynthMethod::Enm:
            return synthesize_enm(exemplar, size, seed);
    }
    return {};
}

}  // namespace tilejet::synth
