#include "tilejet/colour/measurements.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

#include "lcms_context.hpp"
#include "tilejet/colour/cmyk_transform.hpp"

namespace tilejet::colour {

namespace {

// Printer characterisation charts have a few thousand patches (IT8.7/4: 1617).
constexpr double kMaxPatches = 100000;

}  // namespace

std::vector<Measurement> read_measurements(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw ColourError("cannot read measurements '" + path.string() +
                          "': " + std::strerror(errno));
    const std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(in),
                                     std::istreambuf_iterator<char>()};
    return parse_measurements(bytes, path.string());
}

std::vector<Measurement> parse_measurements(std::span<const uint8_t> bytes,
                                            const std::string& name) {
    const std::string where = "measurements '" + name + "'";
    if (bytes.empty()) throw ColourError(where + " is an empty file");
    detail::LcmsContext lcms;
    // LittleCMS's CGATS parser (cmsIT8) reads Argyll's .ti3 as well as IT8 files.
    detail::It8 it8(cmsIT8LoadFromMem(lcms.get(), bytes.data(), cmsUInt32Number(bytes.size())));
    if (!it8) {
        const std::string why = lcms.take_error();
        throw ColourError(where + " is not a CGATS measurement file" +
                          (why.empty() ? "" : ": " + why));
    }
    const char* fields[] = {"CMYK_C", "CMYK_M", "CMYK_Y", "CMYK_K", "LAB_L", "LAB_A", "LAB_B"};
    int column[7];
    for (int f = 0; f < 7; ++f) {
        column[f] = cmsIT8FindDataFormat(it8.get(), fields[f]);
        if (column[f] < 0)
            throw ColourError(where + " has no " + fields[f] + " field: a line profile needs the " +
                              (f < 4 ? "CMYK ink values" : "measured Lab values") +
                              " of each patch");
    }
    // The file says how many patches it holds; the data must bear it out. (A number beyond int
    // was undefined behaviour, found by fuzzing; a large one asked for gigabytes.)
    const double sets = cmsIT8GetPropertyDbl(it8.get(), "NUMBER_OF_SETS");
    if (!(sets >= 1)) throw ColourError(where + " holds no measured patches");
    if (sets > kMaxPatches)
        throw ColourError(where + ": NUMBER_OF_SETS " +
                          cmsIT8GetProperty(it8.get(), "NUMBER_OF_SETS") + " is more than " +
                          std::to_string(int(kMaxPatches)) + " patches");
    const int rows = int(sets);
    std::vector<Measurement> out(static_cast<size_t>(rows));
    for (int r = 0; r < rows; ++r) {
        double v[7];
        for (int f = 0; f < 7; ++f) {
            if (!cmsIT8GetDataRowCol(it8.get(), r, column[f]))
                throw ColourError(where + ": patch " + std::to_string(r + 1) + " of " +
                                  std::to_string(rows) + " (NUMBER_OF_SETS) has no " + fields[f] +
                                  " value");
            v[f] = cmsIT8GetDataRowColDbl(it8.get(), r, column[f]);
        }
        out[size_t(r)] = {v[0], v[1], v[2], v[3], v[4], v[5], v[6]};
    }
    return out;
}

}  // namespace tilejet::colour
