// tilejet render | sample

#include <cstdio>
#include <memory>
#include <optional>

#include "arguments.hpp"
#include "commands.hpp"
#include "image_output.hpp"
#include "tilejet/colour/cmyk_map.hpp"
#include "tilejet/synth/map_file.hpp"
#include "tilejet/synth/sampler.hpp"
#include "tilejet/synth/tile_region.hpp"

namespace tilejet::cli {

namespace {

struct RenderOptions {
    std::string map, output, origin, size, layout = "scatter", intent = "perceptual", proof;
    colour::ColourSettings colour;
    bool bpc = false;
    uint64_t seed = 0;
    std::optional<uint64_t> tile;
    int wall_width = 10, threads = 0;
};

synth::Region region_of(const RenderOptions& o) {
    const Size2 size = parse_size(o.size, "--size");
    if (o.tile) {
        const auto layout = synth::parse_tile_layout(o.layout);
        if (!layout)
            throw std::invalid_argument("--layout '" + o.layout + "': expected scatter or wall");
        return synth::tile_region(o.seed, *o.tile,
                                  {size.width, size.height, *layout, o.wall_width});
    }
    const Point2 origin = parse_point(o.origin, "--origin");
    return {origin.x, origin.y, size.width, size.height};
}

void run_render(const RenderOptions& o) {
    const synth::Region region = region_of(o);
    const synth::TextureMap map = synth::load_texture_map(o.map);
    if (o.colour.output_profile.empty()) {
        if (!o.proof.empty()) throw std::invalid_argument("--proof needs --cmyk PROFILE.icc");
        write_rgb_image(synth::render_region(map, o.seed, region, o.threads), o.output);
        return;
    }
    colour::ColourSettings settings = o.colour;
    const auto intent = colour::parse_intent(o.intent);
    if (!intent)
        throw std::invalid_argument("--intent '" + o.intent +
                                    "': expected perceptual, relative, saturation or absolute");
    settings.intent = *intent;
    settings.black_point_compensation = o.bpc;
    const colour::CmykTransform transform(settings);
    // Convert once, copy many: the map's images go to CMYK, then the tile is only copied.
    const auto cmyk_map = colour::convert_map(map, transform);
    const cv::Mat cmyk = synth::render_region(*cmyk_map, o.seed, region, o.threads);
    write_cmyk_image(cmyk, transform.output_profile_bytes(), o.output);
    if (!o.proof.empty()) write_rgb_image(transform.proof(cmyk), o.proof);
}

}  // namespace

void add_render_commands(CLI::App& app) {
    auto r = std::make_shared<RenderOptions>();
    CLI::App* render = app.add_subcommand("render", "render a tile or any region of the plane");
    render->add_option("MAP", r->map, "texture map file")->required();
    render->add_option("--seed", r->seed, "job seed")->required();
    auto* tile = render->add_option("--tile", r->tile, "tile index in the job");
    auto* origin = render->add_option("--origin", r->origin, "region origin X,Y in px");
    tile->excludes(origin);
    render->add_option("--size", r->size, "region size WxH in px")->required();
    render->add_option("--layout", r->layout, "tile layout: scatter (default) or wall");
    render->add_option("--wall-width", r->wall_width, "tiles per wall row (wall layout)")
        ->check(CLI::Range(1, 1000000));
    render->add_option("--threads", r->threads, "threads (default: all cores)")
        ->check(CLI::Range(0, 1024));
    render
        ->add_option("-o,--output", r->output,
                     ".png or .raw (RGB); with --cmyk .tif (profile embedded) or .raw (C,M,Y,K)")
        ->required();
    render->add_option("--cmyk", r->colour.output_profile, "the line's CMYK ICC profile");
    render->add_option("--source-profile", r->colour.source_profile, "RGB profile (default sRGB)");
    render->add_option("--intent", r->intent,
                       "perceptual (default), relative, saturation, absolute");
    render->add_flag("--bpc", r->bpc, "black point compensation");
    render->add_option("--ink-limit", r->colour.ink_limit_percent,
                       "total ink limit in % (default 300)");
    render->add_option("--curves", r->colour.ink_curves, "per-ink linearization table (TOML)");
    render->add_option("--proof", r->proof, "also write an sRGB soft proof (.png)");
    render->callback([r, render] {
        if (render->count("--tile") + render->count("--origin") != 1)
            throw CLI::ValidationError("render", "give exactly one of --tile K or --origin X,Y");
        run_render(*r);
    });

    auto s = std::make_shared<RenderOptions>();
    CLI::App* sample = app.add_subcommand("sample", "print one pixel of the plane as R G B");
    sample->add_option("MAP", s->map, "texture map file")->required();
    sample->add_option("--seed", s->seed, "job seed")->required();
    sample->add_option("--at", s->origin, "pixel X,Y")->required();
    sample->callback([s] {
        const Point2 at = parse_point(s->origin, "--at");
        const synth::TextureMap map = synth::load_texture_map(s->map);
        synth::Sampler sampler(map, s->seed);
        const synth::Rgb c = sampler.sample(at.x, at.y);
        std::printf("%d %d %d\n", c.r, c.g, c.b);
    });
}

}  // namespace tilejet::cli
