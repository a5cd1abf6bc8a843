#include "fixtures.hpp"

#include <fstream>
#include <random>

#include "tilejet/synth/build.hpp"
#include "tilejet/synth/exemplar.hpp"

namespace tilejet::test {

const cv::Mat& demo_exemplar() {
    static const cv::Mat exemplar = synth::load_exemplar(std::filesystem::path(TILEJET_SOURCE_DIR) /
                                                         "config/demo/green-marble.png");
    return exemplar;
}

const synth::TextureMap& small_map() {
    static const synth::TextureMap map = [] {
        synth::BuildParams params;
        params.cell_size = 64;
        params.patches = 160;
        params.candidates = 3200;
        params.seed = 11;
        return synth::build_texture_map(demo_exemplar(), params);
    }();
    return map;
}

TempDir::TempDir() {
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() /
            ("tilejet-test-" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
}

void write_file(const std::filesystem::path& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
}

}  // namespace tilejet::test
