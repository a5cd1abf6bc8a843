#include "fixtures.hpp"

#include <unistd.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <opencv2/imgproc.hpp>
#include <random>

#include "tilejet/synth/build.hpp"
#include "tilejet/synth/exemplar.hpp"
#include "tilejet/synth/map_file.hpp"

namespace tilejet::test {

const cv::Mat& demo_exemplar() {
    static const cv::Mat exemplar = synth::load_exemplar(
        std::filesystem::path(TILEJET_SOURCE_DIR) / "config/demo/green-marble.png", {});
    return exemplar;
}

namespace {

// A map built by this very test program: CTest runs every test case in a process of its own,
// and some thirty of them start from small_map(), which takes 2 s to build (20 s under the
// sanitizers). The first process to need it saves it in the build tree
// (TILEJET_FIXTURE_CACHE_DIR); the others load it.
// The file is only trusted from a program with the same path, size and modification time (a
// rebuild of any synth code relinks the program), and is written under a temporary name and
// renamed, so processes running side by side never read half a file. Saving and loading are
// lossless (test_map_file.cpp).
synth::TextureMap built_once(const std::string& name,
                             const std::function<synth::TextureMap()>& build) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    if (ec) return build();
    const auto size = fs::file_size(self, ec);
    if (ec) return build();
    const auto stamp = fs::last_write_time(self, ec).time_since_epoch().count();
    if (ec) return build();
    const fs::path dir = TILEJET_FIXTURE_CACHE_DIR;
    fs::create_directories(dir, ec);
    if (ec) return build();
    const fs::path cached = dir / (self.filename().string() + "." + name + "." +
                                   std::to_string(size) + "-" + std::to_string(stamp) + ".tjmap");
    if (fs::exists(cached, ec)) return synth::load_texture_map(cached);
    synth::TextureMap map = build();
    const fs::path partial = cached.string() + "." + std::to_string(::getpid()) + ".part";
    synth::save_texture_map(map, partial);
    fs::rename(partial, cached, ec);
    // Maps of earlier builds of the program are of no more use.
    const std::string prefix = self.filename().string() + "." + name + ".";
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        const std::string file = entry.path().filename().string();
        if (file.starts_with(prefix) && file.ends_with(".tjmap") && entry.path() != cached)
            fs::remove(entry.path(), ec);
    }
    return map;
}

}  // namespace

double correlation_at(const cv::Mat& lab, cv::Point lag) {
    const cv::Rect a(std::max(0, -lag.x), std::max(0, -lag.y), lab.cols - std::abs(lag.x),
                     lab.rows - std::abs(lag.y));
    const cv::Rect b = a + lag;
    const cv::Mat pa = lab(a), pb = lab(b);
    const cv::Scalar ma = cv::mean(pa), mb = cv::mean(pb);
    double cov = 0, va = 0, vb = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            const cv::Vec3f p = pa.at<cv::Vec3f>(y, x), q = pb.at<cv::Vec3f>(y, x);
            for (int c = 0; c < 3; ++c) {
                const double u = p[c] - ma[c], v = q[c] - mb[c];
                cov += u * v, va += u * u, vb += v * v;
            }
        }
    return cov / std::sqrt(va * vb);
}

const synth::TextureMap& small_map() {
    static const synth::TextureMap map = built_once("small_map", [] {
        synth::BuildParams params;
        params.corner_colours = 1;  // the one-image map whose tests came before cell sets
        params.cell_size = 64;
        params.patches = 160;
        params.candidates = 3200;
        params.seed = 11;
        return synth::build_texture_map(demo_exemplar(), params);
    });
    return map;
}

size_t pixels_unlike_sampler(const synth::TextureMap& map, uint64_t seed,
                             const synth::Region& region, const cv::Mat& rendered) {
    synth::Sampler sampler(map, seed);
    size_t unlike = 0;
    for (int y = 0; y < region.height; ++y)
        for (int x = 0; x < region.width; ++x) {
            const synth::Rgb s = sampler.sample(region.x + x, region.y + y);
            const cv::Vec3b r = rendered.at<cv::Vec3b>(y, x);
            unlike += !(s == synth::Rgb{r[0], r[1], r[2]});
        }
    return unlike;
}

void write_file(const std::filesystem::path& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
}

std::string read_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

cv::Mat make_lattice_texture(Basis b, cv::Size size, uint32_t seed, bool ellipse) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0, 6), tile_shift(0, 14);
    std::map<std::pair<int, int>, cv::Vec3d> tile_colour;
    const double det = b.t1.x * b.t2.y - b.t1.y * b.t2.x;
    cv::Mat out(size, CV_8UC3);
    for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x) {
            // Lattice coordinates of the pixel: solve x = u t1 + v t2.
            const double u = (x * b.t2.y - y * b.t2.x) / det, v = (y * b.t1.x - x * b.t1.y) / det;
            const int iu = int(std::floor(u)), iv = int(std::floor(v));
            const double fu = u - iu, fv = v - iv;
            auto [it, fresh] = tile_colour.try_emplace({iu, iv});
            if (fresh) it->second = {tile_shift(rng), tile_shift(rng), tile_shift(rng)};
            bool inside;
            if (ellipse) {
                const double du = (fu - 0.5) / 0.42, dv = (fv - 0.5) / 0.42;
                inside = du * du + dv * dv < 1;
            } else {
                inside = fu > 0.08 && fu < 0.92 && fv > 0.1 && fv < 0.9;
            }
            const cv::Vec3d base =
                inside ? cv::Vec3d(170, 80, 60) + it->second : cv::Vec3d(200, 200, 190);
            cv::Vec3b& px = out.at<cv::Vec3b>(y, x);
            for (int c = 0; c < 3; ++c)
                px[c] = cv::saturate_cast<uint8_t>(base[c] + noise(rng));
        }
    return out;
}

cv::Mat make_course_texture(double pitch, cv::Size size, uint32_t seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0, 6), brick_shift(0, 18);
    std::uniform_int_distribution<int> length(24, 60);
    const cv::Vec3d mortar(200, 200, 190), brick(170, 80, 60);
    cv::Mat out(size, CV_8UC3);
    const int courses = int(std::ceil(size.height / pitch)) + 1;
    for (int course = 0; course < courses; ++course) {
        // Where this course's joints fall, and each brick's colour.
        std::vector<std::pair<int, cv::Vec3d>> bricks;  // (start x, colour)
        for (int x = -length(rng); x < size.width; x += length(rng))
            bricks.push_back(
                {x, brick + cv::Vec3d(brick_shift(rng), brick_shift(rng), brick_shift(rng))});
        const int y0 = int(std::ceil(course * pitch)), y1 = int(std::ceil((course + 1) * pitch));
        for (int y = y0; y < std::min(y1, size.height); ++y) {
            const bool bed_joint = y - course * pitch < 3;
            size_t b = 0;
            for (int x = 0; x < size.width; ++x) {
                while (b + 1 < bricks.size() && bricks[b + 1].first <= x)
                    ++b;
                const bool head_joint = x - bricks[b].first < 3;
                const cv::Vec3d base = bed_joint || head_joint ? mortar : bricks[b].second;
                cv::Vec3b& px = out.at<cv::Vec3b>(y, x);
                for (int c = 0; c < 3; ++c)
                    px[c] = cv::saturate_cast<uint8_t>(base[c] + noise(rng));
            }
        }
    }
    return out;
}

bool same_lattice(const synth::Lattice& found, Basis truth, double tol) {
    auto on_truth = [&](cv::Point v) {
        for (int a = -4; a <= 4; ++a)
            for (int b = -4; b <= 4; ++b) {
                const cv::Point2d p = a * truth.t1 + b * truth.t2;
                if (std::hypot(p.x - v.x, p.y - v.y) <= tol) return true;
            }
        return false;
    };
    const double true_area = std::abs(truth.t1.x * truth.t2.y - truth.t1.y * truth.t2.x);
    return on_truth(found.v1) && on_truth(found.v2) &&
           std::abs(found.area() - true_area) < 0.1 * true_area;
}

cv::Vec3d mean_lab(const cv::Mat& rgb) {
    cv::Mat unit, lab;
    rgb.convertTo(unit, CV_32FC3, 1.0 / 255);
    cv::cvtColor(unit, lab, cv::COLOR_RGB2Lab);
    const cv::Scalar m = cv::mean(lab);
    return {m[0], m[1], m[2]};
}

bool same_bytes(const cv::Mat& a, const cv::Mat& b) {
    return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

}  // namespace tilejet::test
