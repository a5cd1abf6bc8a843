#include "embedded_profile.hpp"

#include <zlib.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <string>

#include "image_containers.hpp"
#include "tilejet/synth/error.hpp"

namespace tilejet::synth::detail {

namespace {

[[noreturn]] void damaged_profile(const std::filesystem::path& path, const std::string& why) {
    throw SynthError("exemplar '" + path.string() + "': embedded ICC profile is damaged (" + why +
                     ")");
}

std::vector<uint8_t> inflate_all(const uint8_t* data, size_t size,
                                 const std::filesystem::path& path) {
    constexpr size_t kMaxProfile = 16u << 20;  // real profiles are kilobytes to a few MB
    z_stream z{};
    if (inflateInit(&z) != Z_OK) damaged_profile(path, "zlib");
    std::unique_ptr<z_stream, decltype(&inflateEnd)> guard(&z, inflateEnd);
    z.next_in = const_cast<Bytef*>(data);
    z.avail_in = uInt(size);
    std::vector<uint8_t> out;
    int status = Z_OK;
    while (status == Z_OK) {
        if (out.size() >= kMaxProfile) damaged_profile(path, "larger than 16 MB");
        const size_t before = out.size();
        out.resize(before + 65536);
        z.next_out = out.data() + before;
        z.avail_out = 65536;
        status = inflate(&z, Z_NO_FLUSH);
        out.resize(before + (65536 - z.avail_out));
    }
    if (status != Z_STREAM_END) damaged_profile(path, "the compressed data does not inflate");
    return out;
}

std::vector<uint8_t> profile_from_png(const std::vector<uint8_t>& f,
                                      const std::filesystem::path& path) {
    std::vector<uint8_t> profile;
    for_each_png_chunk(f, [&](std::string_view type, const uint8_t* data, size_t length) {
        if (type != "iCCP") return false;
        const void* nul = std::memchr(data, 0, std::min<size_t>(length, 80));
        if (!nul) damaged_profile(path, "iCCP chunk without a profile name");
        const size_t name = size_t(static_cast<const uint8_t*>(nul) - data);
        if (name + 2 > length || data[name + 1] != 0)
            damaged_profile(path, "unknown iCCP compression");
        profile = inflate_all(data + name + 2, length - name - 2, path);
        return true;
    });
    return profile;
}

std::vector<uint8_t> profile_from_jpeg(const std::vector<uint8_t>& f,
                                       const std::filesystem::path& path) {
    static const char kTag[] = "ICC_PROFILE";  // with its NUL: 12 bytes
    std::map<int, std::vector<uint8_t>> pieces;
    int count = 0;
    for_each_jpeg_segment(f, [&](uint8_t marker, const uint8_t* data, size_t size) {
        if (marker == 0xE2 && size > 14 && std::memcmp(data, kTag, 12) == 0) {
            const int seq = data[12], total = data[13];
            if (seq < 1 || seq > total || (count && total != count))
                damaged_profile(path, "APP2 sequence");
            count = total;
            pieces[seq].assign(data + 14, data + size);
        }
        return false;
    });
    if (pieces.empty()) return {};
    if (int(pieces.size()) != count) damaged_profile(path, "missing APP2 ICC segments");
    std::vector<uint8_t> out;
    for (auto& [seq, bytes] : pieces)
        out.insert(out.end(), bytes.begin(), bytes.end());
    return out;
}

std::vector<uint8_t> profile_from_tiff(const std::filesystem::path& path) {
    const TiffFile tif = open_tiff(path);
    if (!tif) return {};
    uint32_t size = 0;
    void* data = nullptr;
    if (!TIFFGetField(tif.get(), TIFFTAG_ICCPROFILE, &size, &data) || !data) return {};
    const auto* p = static_cast<const uint8_t*>(data);
    return {p, p + size};
}

}  // namespace

std::vector<uint8_t> read_embedded_profile(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    const std::vector<uint8_t> f((std::istreambuf_iterator<char>(in)),
                                 std::istreambuf_iterator<char>());
    if (is_tiff(f)) return profile_from_tiff(path);
    return parse_embedded_profile(f, path);
}

std::vector<uint8_t> parse_embedded_profile(const std::vector<uint8_t>& f,
                                            const std::filesystem::path& path) {
    if (is_png(f)) return profile_from_png(f, path);
    if (is_jpeg(f)) return profile_from_jpeg(f, path);
    return {};
}

}  // namespace tilejet::synth::detail
