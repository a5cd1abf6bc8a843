// tilejet analyze: the lattice of an exemplar, as one JSON object.

#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "tilejet/synth/exemplar.hpp"
#include "tilejet/synth/lattice.hpp"

namespace tilejet::cli {

void add_analyze_commands(CLI::App& app) {
    auto path = std::make_shared<std::string>();
    CLI::App* analyze = app.add_subcommand(
        "analyze", "detect an exemplar's lattice (brick, mosaic, textile) and its regularity");
    analyze->add_option("EXEMPLAR", *path, "PNG, JPEG or TIFF exemplar")->required();
    analyze->callback([path] {
        const synth::Lattice l = synth::detect_lattice(synth::load_exemplar(*path));
        nlohmann::ordered_json j;
        j["v1"] = {l.v1.x, l.v1.y};
        j["v2"] = {l.v2.x, l.v2.y};
        j["score"] = l.score;
        j["kind"] = synth::lattice_kind_name(l.kind);
        if (l.appearance_regularity) j["A"] = *l.appearance_regularity;
        if (l.geometry_regularity) j["G"] = *l.geometry_regularity;
        if (l.kind == synth::LatticeKind::Stochastic)
            j["note"] = "no lattice found: stochastic texture, unit vectors reported";
        std::printf("%s\n", j.dump().c_str());
    });
}

}  // namespace tilejet::cli
