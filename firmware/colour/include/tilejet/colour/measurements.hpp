#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace tilejet::colour {

// One measured patch of a printed and fired chart: the ink values sent (percent) and the
// colour measured on the tile (CIELab, D50).
struct Measurement {
    double c = 0, m = 0, y = 0, k = 0;
    double L = 0, a = 0, b = 0;
};

// Reads a CGATS measurement file (ArgyllCMS .ti3 or IT8.7/4 style) with the fields CMYK_C,
// CMYK_M, CMYK_Y, CMYK_K, LAB_L, LAB_A, LAB_B. Throws ColourError naming the file and any
// missing field.
std::vector<Measurement> read_measurements(const std::filesystem::path& path);
// The same from bytes already read; `name` names them in messages.
std::vector<Measurement> parse_measurements(std::span<const uint8_t> bytes,
                                            const std::string& name);

}  // namespace tilejet::colour
