#pragma once

// The exactly-once check of a print log, shared by the daemon's integration tests and the soak:
// every tile index of a job printed, each with the SHA-256 of the separations rendered here
// through synth and colour directly (not through the daemon's code), and a tile printed more
// than once only when the daemon spoiled it (e-stop under the heads), then with the same bytes.
#include <openssl/evp.h>

#include <algorithm>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tilejet/colour/cmyk_map.hpp"
#include "tilejet/synth/map_file.hpp"
#include "tilejet/synth/sampler.hpp"
#include "tilejet/synth/tile_region.hpp"

namespace tilejet::test {

inline std::string sha256_hex(const std::uint8_t* data, size_t size) {
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int length = 0;
    EVP_Digest(data, size, digest, &length, EVP_sha256(), nullptr);
    std::string out;
    static const char* hex = "0123456789abcdef";
    for (unsigned i = 0; i < length; ++i) {
        out += hex[digest[i] >> 4];
        out += hex[digest[i] & 15];
    }
    return out;
}

// Offline renders of a job's scatter-layout tiles: the map converted to the line's CMYK once.
class ReferenceRenderer {
  public:
    ReferenceRenderer(const std::string& map_path, const std::string& profile, int side_px)
        : side_(side_px) {
        const synth::TextureMap map = synth::load_texture_map(map_path);
        colour::ColourSettings settings;
        settings.output_profile = profile;
        const colour::CmykTransform transform(settings);
        cmyk_ = colour::convert_map(map, transform);
    }

    std::string hash(std::uint64_t seed, std::uint64_t index) const {
        const auto region = synth::tile_region(seed, index, {side_, side_});
        const cv::Mat tile = synth::render_region(*cmyk_, seed, region, 1);
        return sha256_hex(tile.data, tile.total() * tile.elemSize());
    }

  private:
    int side_;
    std::shared_ptr<const synth::TextureMap> cmyk_;
};

struct PrintLogResult {
    int indices_printed = 0;            // distinct indices of the job in the log
    int reprints = 0;                   // prints beyond the first of an index
    std::vector<std::string> problems;  // empty: exactly once, right bytes
};

// `reference[k]`: the expected SHA-256 of tile k; `spoiled`: reprints the daemon reported.
inline PrintLogResult check_print_log(const std::vector<nlohmann::json>& log, std::int64_t job_id,
                                      const std::vector<std::string>& reference,
                                      std::int64_t spoiled) {
    PrintLogResult result;
    const std::string job = "job-" + std::to_string(job_id);
    const int tiles = int(reference.size());
    std::map<int, int> count;
    std::map<int, std::string> line_tiles;  // where each index was printed, for the message
    for (const nlohmann::json& entry : log) {
        if (entry.value("status", "") != "printed" || entry.value("job", "") != job) continue;
        const int k = entry.value("tile", -1);
        if (k < 0 || k >= tiles) {
            result.problems.push_back(job + ": tile index " + std::to_string(k) +
                                      " is outside the job");
            continue;
        }
        if (entry.value("sha256", "") != reference[size_t(k)])
            result.problems.push_back(job + " tile " + std::to_string(k) +
                                      ": separations differ from the offline render");
        ++count[k];
        line_tiles[k].append(" ").append(entry.value("time", "")).append("@line_tile ");
        line_tiles[k].append(std::to_string(entry.value("line_tile", -1)));
    }
    std::string reprinted;
    for (int k = 0; k < tiles; ++k) {
        if (count[k] == 0)
            result.problems.push_back(job + " tile " + std::to_string(k) + " never printed");
        if (count[k] > 1) {
            reprinted.append("\n  tile ").append(std::to_string(k));
            reprinted.append(" printed ").append(std::to_string(count[k])).append(" times:");
            reprinted.append(line_tiles[k]);
        }
        result.reprints += std::max(0, count[k] - 1);
    }
    result.indices_printed =
        int(std::count_if(count.begin(), count.end(), [](const auto& c) { return c.second > 0; }));
    if (result.reprints != spoiled)
        result.problems.push_back(job + ": " + std::to_string(result.reprints) +
                                  " tile(s) printed more than once, the daemon spoiled " +
                                  std::to_string(spoiled) + reprinted);
    return result;
}

}  // namespace tilejet::test
