// Frame patches (strip_continuation.hpp): a cell image's strip continued into the cell from the
// source, cut against the image, shown by hash.

#include <catch2/catch.hpp>
#include <filesystem>
#include <set>

#include "cell_set.hpp"
#include "fixtures.hpp"
#include "grain.hpp"
#include "strip_continuation.hpp"
#include "tilejet/synth/build.hpp"
#include "tilejet/synth/exemplar.hpp"
#include "tilejet/synth/internal/lab.hpp"
#include "tilejet/synth/map_file.hpp"
#include "tilejet/synth/sampler.hpp"

using namespace tilejet::synth;
using namespace tilejet::synth::detail;

namespace {

constexpr CellEdge kEdges[] = {CellEdge::top, CellEdge::bottom, CellEdge::left, CellEdge::right};

cv::Mat corpus_design(const char* name) {
    return load_exemplar(std::filesystem::path(TILEJET_SOURCE_DIR) / "tests/quality/corpus" / name,
                         {});
}

// A 384 px design and 96 px cells: a strip of 116 px is one window of the source, as on the
// corpus's 256 px cells.
TextureMap marble_map(int frame_patches, uint64_t seed = 1) {
    BuildParams p;
    p.cell_size = 96;
    p.corner_colours = 2;  // 36 images (96 px cells get 3 by default: 168, four times the build)
    p.seed = seed;
    p.frame_patches = frame_patches;
    return build_texture_map(corpus_design("marble.png"), p);
}

}  // namespace

TEST_CASE("a strip's offset says where every image showing it copied it from",
          "[frame_patches][cell_set]") {
    const cv::Mat source = corpus_design("marble.png");
    const cv::Mat lab = to_lab(source);
    CellSetParams params;
    params.cell = {96, 96};
    params.seed = 2;
    const CellSet set(source, lab, params);
    int checked = 0;
    for (size_t m = 0; m < set.size(); ++m)
        for (const CellEdge edge : kEdges) {
            const std::optional<cv::Point> offset = set.strip_offset(m, edge);
            REQUIRE(offset);
            // The cell's outer pixels are its strips' (locked), away from the corner cores.
            const cv::Mat& image = set.image(m);
            for (int t = set.frame(); t < 96 - set.frame(); ++t) {
                const cv::Point at = edge == CellEdge::top      ? cv::Point(t, 0)
                                     : edge == CellEdge::bottom ? cv::Point(t, 95)
                                     : edge == CellEdge::left   ? cv::Point(0, t)
                                                                : cv::Point(95, t);
                INFO("image " << m << " edge " << int(edge) << " at " << at);
                REQUIRE(image.at<cv::Vec3b>(at) == source.at<cv::Vec3b>(at + *offset));
                ++checked;
            }
        }
    CHECK(checked == int(set.size()) * 4 * (96 - 2 * set.frame()));
}

TEST_CASE("frame patches lie inside their cell and leave its border as its neighbours see it",
          "[frame_patches][cell_set]") {
    const TextureMap map = marble_map(4);
    REQUIRE(map.cell_images.size() == 36);
    size_t patches = 0, border_pixels = 0, strip_pixels = 0, deep = 0;
    std::set<int> depths;
    for (const CellImage& image : map.cell_images) {
        // In both sets: inside the cell no neighbour's patch can meet them.
        REQUIRE(image.a.size() == image.b.size());
        for (const Patch& p : image.a.patches) {
            ++patches;
            REQUIRE(p.x >= 0);
            REQUIRE(p.y >= 0);
            REQUIRE(p.x + p.width <= 96);
            REQUIRE(p.y + p.height <= 96);
            for (int y = 0; y < p.height; ++y)
                for (int x = 0; x < p.width; ++x) {
                    if (!p.covers(x, y)) continue;
                    const int cx = p.x + x, cy = p.y + y;
                    const int from_border = std::min({cx, cy, 95 - cx, 95 - cy});
                    // The cell's outer pixels, which its neighbours meet, are never covered.
                    REQUIRE(from_border > 0);
                    // Next to them it reaches where the cell's own cut into its strip runs
                    // (from the pixel after the outer one on: kept_depths()), to hide it.
                    if (from_border == 1) {
                        ++border_pixels;
                        strip_pixels += map.source.at<cv::Vec3b>(p.src_y + y, p.src_x + x) ==
                                        image.pixels.at<cv::Vec3b>(cy, cx);
                    }
                }
            // How far in from its edge it reaches: the nearest of its box's far sides.
            const int depth = std::min({p.y + p.height, 96 - p.y, p.x + p.width, 96 - p.x});
            depths.insert(depth);
            // Beyond the frame (a tenth of the cell): they move the cut off the strip.
            deep += depth > 96 / 10;
        }
    }
    INFO(patches << " patches, " << border_pixels << " of their pixels next to the border ("
                 << strip_pixels << " the strip's), " << deep << " reaching past the frame, "
                 << depths.size() << " depths");
    CHECK(patches >= 36 * 4 * 2);
    CHECK(border_pixels > 0);
    CHECK(strip_pixels > 0);
    CHECK(deep == patches);
    CHECK(depths.size() >= 8);  // the cut moves to many depths, not one new line
}

TEST_CASE("a set with frame patches renders as it samples, through its file",
          "[frame_patches][cell_set][sampler]") {
    const TextureMap map = decode_texture_map(encode_texture_map(marble_map(4, 3)), "frame.tjmap");
    const Region region{-517, 203, 611, 389};
    const cv::Mat out = render_region(map, 77, region, 2);
    REQUIRE(tilejet::test::pixels_unlike_sampler(map, 77, region, out) == 0);
    // Shown: some of the plane is patches, not its cell images.
    const cv::Mat bare = render_region(marble_map(0, 3), 77, region, 2);
    CHECK(cv::norm(out, bare, cv::NORM_L1) > 0);
    // The same build on one thread is the same map.
    BuildParams p;
    p.cell_size = 96;
    p.corner_colours = 2;  // as marble_map()
    p.seed = 3;
    p.frame_patches = 4;
    p.threads = 1;
    CHECK(build_texture_map(corpus_design("marble.png"), p).id == map.id);
}

TEST_CASE(
    "a set of a design without a grain has no frame patches unless asked for, bad counts "
    "are refused",
    "[frame_patches][cell_set]") {
    BuildParams defaults;
    REQUIRE(defaults.frame_patches == BuildParams::kFrameFromGrain);
    for (const CellImage& image : marble_map(defaults.frame_patches).cell_images) {
        CHECK(image.a.patches.empty());
        CHECK(image.b.patches.empty());
    }
    BuildParams p;
    p.cell_size = 96;
    for (const int bad : {-2, 17}) {
        p.frame_patches = bad;
        CHECK_THROWS_WITH(build_texture_map(corpus_design("marble.png"), p),
                          Catch::Contains("--frame-patches " + std::to_string(bad)));
    }
    p.frame_patches = 4;
    p.frame_active = -1;
    CHECK_THROWS_WITH(build_texture_map(corpus_design("marble.png"), p),
                      Catch::Contains("--frame-active"));
}

TEST_CASE("smoothed cell images get no frame patches: their frames no longer copy the source",
          "[frame_patches][cell_set]") {
    BuildParams p;
    p.cell_size = 96;
    p.corner_colours = 2;  // 36 images are as many as this needs, in a quarter of the build
    p.frame_patches = 4;
    p.smooth_steps = true;
    const TextureMap map = build_texture_map(corpus_design("marble.png"), p);
    REQUIRE(map.cell_images.size() > 1);
    for (const CellImage& image : map.cell_images) {
        CHECK(image.a.patches.empty());
        CHECK(image.b.patches.empty());
    }
}

TEST_CASE("of the corpus's designs off a lattice only the wood has a grain",
          "[frame_patches][grain]") {
    const std::filesystem::path corpus =
        std::filesystem::path(TILEJET_SOURCE_DIR) / "tests/quality/corpus";
    for (const auto& entry : std::filesystem::directory_iterator(corpus)) {
        if (entry.path().extension() != ".png") continue;
        const std::string name = entry.path().filename().string();
        if (name == "brick-wall.png") continue;  // a lattice: its courses are its grain
        INFO(name);
        const double alignment = grain_alignment(load_exemplar(entry.path(), {}));
        if (name == "wood.png") {
            CHECK(alignment > 0.7);
            const double degrees = grain_direction(load_exemplar(entry.path(), {})).degrees;
            CHECK((degrees < 20 || degrees > 160));  // its planks run along the rows
        } else
            CHECK(alignment < 0.3);
    }
}

TEST_CASE(
    "a set of a design with a grain gets frame patches by default on the edges across it, none "
    "when told 0",
    "[frame_patches][cell_set]") {
    // Wood's grain breaks at every cell border across it: frame patches move the cells' cuts
    // off one line there (sessions 43 and 44). 96 px cells: a strip is one window of the source.
    const auto wood_map = [](int frame_patches) {
        BuildParams p;
        p.cell_size = 96;
        p.corner_colours = 2;
        p.frame_patches = frame_patches;
        return build_texture_map(corpus_design("wood.png"), p);
    };
    const auto patches_of = [](const TextureMap& map) {
        size_t n = 0;
        for (const CellImage& image : map.cell_images)
            n += image.a.patches.size() + image.b.patches.size();
        return n;
    };
    const TextureMap by_default = wood_map(BuildParams::kFrameFromGrain);
    const TextureMap asked = wood_map(4);
    CHECK(patches_of(by_default) > by_default.cell_images.size());
    CHECK(by_default.id == asked.id);
    // Its planks run along the rows: patches on the upright edges only, each running along its
    // edge (at least half of it) further than it reaches in (at most a quarter of the cell).
    size_t upright = 0, lying = 0;
    for (const CellImage& image : by_default.cell_images)
        for (const Patch& patch : image.a.patches)
            ++(patch.height > patch.width ? upright : lying);
    CHECK(upright > 0);
    CHECK(lying == 0);
    CHECK(patches_of(wood_map(0)) == 0);
}
