#pragma once

#include <cstddef>
#include <filesystem>
#include <vector>

#include "tilejet/colour/measurements.hpp"

namespace tilejet::colour {

// How well an output profile predicts the measured colours: CIEDE2000 between each patch's
// measurement and the profile's absolute-colorimetric prediction for its ink values.
struct ProfileReport {
    size_t patches = 0;
    double mean = 0, p95 = 0, max = 0;
};

ProfileReport check_profile(const std::filesystem::path& profile,
                            const std::vector<Measurement>& measurements);

}  // namespace tilejet::colour
