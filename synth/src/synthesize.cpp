#include "tilejet/synth/synthesize.hpp"

#include <string>

#include "tilejet/synth/enm.hpp"
#include "tilejet/synth/error.hpp"
#include "tilejet/synth/lattice.hpp"
#include "tilejet/synth/quilt.hpp"
#include "tilejet/synth/rsgf.hpp"

namespace tilejet::synth {

std::string_view synth_method_name(SynthMethod method) {
    switch (method) {
        case SynthMethod::Quilt:
            return "quilt";
        case SynthMethod::Rsgf:
            return "rsgf";
        case SynthMethod::Enm:
            return "enm";
    }
    return "quilt";
}

SynthMethod parse_synth_method(std::string_view text, std::string_view option) {
    for (SynthMethod m : {SynthMethod::Quilt, SynthMethod::Rsgf, SynthMethod::Enm})
        if (text == synth_method_name(m)) return m;
    throw SynthError(std::string(option) + " '" + std::string(text) +
                     "': expected quilt, rsgf or enm");
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
