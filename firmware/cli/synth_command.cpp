// tilejet synth: an exemplar enlarged by one of the offline synthesizers, as an image.

#include <chrono>
#include <cstdio>
#include <memory>

#include "arguments.hpp"
#include "commands.hpp"
#include "image_output.hpp"
#include "tilejet/colour/exemplar_profile.hpp"
#include "tilejet/synth/synthesize.hpp"

namespace tilejet::cli {

namespace {

struct SynthOptions {
    std::string exemplar, method, size, output;
    uint64_t seed = 1;
};

void run_synth(const SynthOptions& o) {
    // Options first: a typo should not wait for the exemplar to load.
    const synth::SynthMethod method = synth::parse_synth_method(o.method, "--method");
    const Size2 size = parse_size(o.size, "--size");
    const auto start = std::chrono::steady_clock::now();
    const cv::Mat out = synth::synthesize(colour::load_exemplar(o.exemplar), method,
                                          {size.width, size.height}, o.seed);
    write_rgb_image(out, o.output);
    std::printf("wrote %s: %dx%d by %s, seed %ju, %.1f s\n", o.output.c_str(), out.cols, out.rows,
                o.method.c_str(), uintmax_t(o.seed),
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace

void add_synth_commands(CLI::App& app) {
    auto o = std::make_shared<SynthOptions>();
    CLI::App* s = app.add_subcommand(
        "synth", "synthesize a larger texture from an exemplar (quilting, rsgf or enm)");
    s->add_option("EXEMPLAR", o->exemplar, "PNG, JPEG or TIFF exemplar")->required();
    s->add_option("--method", o->method,
                  "quilt: image quilting; rsgf: lattice-aligned random blocks, gaps filled by "
                  "border match; enm: exact neighbourhood matching, pixel by pixel")
        ->required();
    s->add_option("--size", o->size, "output size WxH in px")->required();
    s->add_option("--seed", o->seed, "seed (default 1); the same seed gives the same bytes");
    s->add_option("-o,--output", o->output, "image to write (.png or .raw)")->required();
    s->callback([o] { run_synth(*o); });
}

}  // namespace tilejet::cli
