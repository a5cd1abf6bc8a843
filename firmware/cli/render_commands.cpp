// tilejet render | sample

#include <cstdio>
#include <memory>
#include <optional>

#include "arguments.hpp"
#include "commands.hpp"
#include "image_output.hpp"
#include "tilejet/synth/map_file.hpp"
#include "tilejet/synth/sampler.hpp"
#include "tilejet/synth/tile_region.hpp"

namespace tilejet::cli {

namespace {

struct RenderOptions {
    std::string map, output, origin, size, layout = "scatter";
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
    write_rgb_image(synth::render_region(map, o.seed, region, o.threads), o.output);
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
    render->add_option("-o,--output", r->output, ".png or .raw (interleaved RGB)")->required();
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
