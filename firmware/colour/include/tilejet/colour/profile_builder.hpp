#pragma once

#include <filesystem>
#include <string>

namespace tilejet::colour {

struct ProfileBuildOptions {
    double ink_limit_percent = 300;  // total ink the profile's separations may use
    std::string quality = "m";       // colprof -q: l(ow), m(edium), h(igh), u(ltra)
    std::string description;         // profile description; empty: from the file name
};

// Builds a CMYK output profile from CGATS measurements (.ti3) with ArgyllCMS colprof.
// Throws ColourError naming the file, with colprof's last words when it fails.
void build_profile(const std::filesystem::path& measurements, const std::filesystem::path& output,
                   const ProfileBuildOptions& options);

}  // namespace tilejet::colour
