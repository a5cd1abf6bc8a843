#pragma once

#include <filesystem>
#include <opencv2/core/mat.hpp>
#include <string>

#include "../temp_dir.hpp"
#include "tilejet/synth/lattice.hpp"
#include "tilejet/synth/sampler.hpp"
#include "tilejet/synth/texture_map.hpp"

namespace tilejet::test {

// The demo exemplar shipped in config/demo (R,G,B).
const cv::Mat& demo_exemplar();

// The mean CIELab colour of an 8-bit R,G,B image (OpenCV's D65 sRGB conversion).
cv::Vec3d mean_lab(const cv::Mat& rgb);

// A small one-image map of the demo exemplar (64 px cells, 160 patches), built once per run.
const synth::TextureMap& small_map();

// How many pixels of `rendered` (render_region of `region`, R,G,B) differ from what
// Sampler::sample gives for the same map and seed.
size_t pixels_unlike_sampler(const synth::TextureMap& map, uint64_t seed,
                             const synth::Region& region, const cv::Mat& rendered);

// Pearson correlation in CIELab (channels pooled) between `lab` (CV_32FC3) and itself shifted
// by `lag`, over their overlap: what autocorrelation_peak measures at each lag.
double correlation_at(const cv::Mat& lab, cv::Point lag);

void write_file(const std::filesystem::path& path, const std::string& bytes);
// The whole of a file's bytes ("" when it cannot be read).
std::string read_file(const std::filesystem::path& path);

// A lattice's true (possibly fractional) translation vectors.
struct Basis {
    cv::Point2d t1, t2;
};

// A near-regular texture on lattice (t1, t2): each tile a rounded "brick" or "stone" (an
// ellipse filling most of the tile) in mortar, every tile with its own colour shift, plus
// per-pixel colour noise, cropped to `size` (not a whole number of periods).
cv::Mat make_lattice_texture(Basis b, cv::Size size, uint32_t seed, bool ellipse = false);

// Brick laid in horizontal courses `pitch` px apart (a fraction of a pixel allowed), bricks of
// random length (24 to 60 px) in mortar, so joints fall anywhere along a course: courses, no
// two-way lattice. Each brick has its own colour; per-pixel noise.
cv::Mat make_course_texture(double pitch, cv::Size size, uint32_t seed);

// Whether every detected vector is (within tol px) a lattice point of the truth and the two
// lattices have the same cell area: then they are the same lattice up to sign, swap and adding
// one vector to the other.
bool same_lattice(const synth::Lattice& found, Basis truth, double tol = 1.5);

// Whether two images have the same size, type and bytes.
bool same_bytes(const cv::Mat& a, const cv::Mat& b);

}  // namespace tilejet::test
