#pragma once

#include <filesystem>
#include <opencv2/core/mat.hpp>
#include <string>

#include "tilejet/synth/texture_map.hpp"

namespace tilejet::test {

// The demo exemplar shipped in config/demo (R,G,B).
const cv::Mat& demo_exemplar();

// A small map of the demo exemplar (64 px cells, 160 patches), built once per test run.
const synth::TextureMap& small_map();

// A fresh directory under the system temp dir, removed when the object goes away.
class TempDir {
  public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return path_; }
    std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

  private:
    std::filesystem::path path_;
};

void write_file(const std::filesystem::path& path, const std::string& bytes);

}  // namespace tilejet::test
