#pragma once

// The colour pipeline as one LittleCMS transform: source RGB profile -> line CMYK profile
// (intent, black point compensation) -> per-ink linearization -> total ink limit.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "tilejet/colour/colour_settings.hpp"

namespace tilejet::colour {

// A profile, curves or setting that cannot be used. The message names the file or setting.
class ColourError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

class CmykTransform {
  public:
    explicit CmykTransform(const ColourSettings& settings);
    ~CmykTransform();
    CmykTransform(const CmykTransform&) = delete;
    CmykTransform& operator=(const CmykTransform&) = delete;

    // 8-bit R,G,B -> 8-bit C,M,Y,K; a pure function of each pixel, safe from several threads.
    void convert(const uint8_t* rgb, uint8_t* cmyk, size_t pixels) const;
    cv::Mat to_cmyk(const cv::Mat& rgb) const;  // CV_8UC3 -> CV_8UC4
    // Soft proof: CMYK back through the output profile to sRGB (for previews on a screen).
    cv::Mat proof(const cv::Mat& cmyk) const;  // CV_8UC4 -> CV_8UC3

    const ColourSettings& settings() const { return settings_; }
    const std::vector<uint8_t>& output_profile_bytes() const { return output_icc_; }
    // Identifies the pipeline: a hash of the profiles' bytes, curves and settings.
    const std::string& key() const { return key_; }
    int ink_limit_value() const;  // the limit in 8-bit ink units: C+M+Y+K <= this

  private:
    struct Handles;
    ColourSettings settings_;
    std::vector<uint8_t> output_icc_;
    std::string key_;
    std::unique_ptr<Handles> handles_;
};

}  // namespace tilejet::colour
