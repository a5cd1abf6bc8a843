#pragma once

// The texture map file (docs/design.md section 2.7): magic, format version, a section table, each
// section zlib-compressed with its length and CRC-32, and the map id (SHA-256 of the content).
// Loading never trusts the file: a truncated, corrupted or future-version file is a MapFileError
// whose message names the file and what is wrong with it.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "tilejet/synth/error.hpp"
#include "tilejet/synth/texture_map.hpp"

namespace tilejet::synth {

class MapFileError : public SynthError {
  public:
    using SynthError::SynthError;
};

// 2: corner-coloured cell sets (CSET); 3: their variant rule (CSET); 4: cell images coded
// against the source (section flag, cell_image_coding.hpp). A map is written with the
// lowest version that holds it, so maps without the newer fields still open in older tilejets.
inline constexpr uint32_t kMapFormatVersion = 4;

// Computes and sets map.id from the map's content.
void assign_map_id(TextureMap& map);
// The format version a map is written with: the lowest that holds what it has.
uint32_t format_version_of(const TextureMap& map);

std::vector<uint8_t> encode_texture_map(const TextureMap& map);
// `name` is what error messages call the data (usually the file's path).
TextureMap decode_texture_map(std::span<const uint8_t> bytes, const std::string& name);

// Writes atomically (temporary file, then rename) so a crash never leaves half a map.
void save_texture_map(const TextureMap& map, const std::filesystem::path& path);
TextureMap load_texture_map(const std::filesystem::path& path);

}  // namespace tilejet::synth
