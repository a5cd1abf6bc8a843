#include "embedded_profile.hpp"

#include <tiffio.h>
#include <zlib.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <string>

#include "tilejet/synth/error.hpp"

namespace tilejet::synth::detail {

namespace {

uint32_t be32(const uint8_t* p) {
    return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | uint32_t(p[3]);
}

[[noreturn]] void damaged(const std::filesystem::path& path, const std::string& why) {
    throw SynthError("exemplar '" + path.string() + "': embedded ICC profile is damaged (" + why +
                     ")");
}

std::vector<uint8_t> inflate_all(const uint8_t* data, size_t size,
                                 const std::filesystem::path& path) {
    constexpr size_t kMaxProfile = 16u << 20;  // real profiles are kilobytes to a few MB
    z_stream z{};
    if (inflateInit(&z) != Z_OK) damaged(path, "zlib");
    std::unique_ptr<z_stream, decltype(&inflateEnd)> guard(&z, inflateEnd);
    z.next_in = const_cast<Bytef*>(data);
    z.avail_in = uInt(size);
    std::vector<uint8_t> out;
    int status = Z_OK;
    while (status == Z_OK) {
        if (out.size() >= kMaxProfile) damaged(path, "larger than 16 MB");
        const size_t before = out.size();
        out.resize(before + 65536);
        z.next_out = out.data() + before;
        z.avail_out = 65536;
        status = inflate(&z, Z_NO_FLUSH);
        out.resize(before + (65536 - z.avail_out));
    }
    if (status != Z_STREAM_END) damaged(path, "the compressed data does not inflate");
    return out;
}

std::vector<uint8_t> from_png(const std::vector<uint8_t>& f, const std::filesystem::path& path) {
    for (size_t at = 8; at + 12 <= f.size();) {
        const uint32_t length = be32(&f[at]);
        if (length > f.size() - at - 12) break;  // truncated: OpenCV reports the pixels' damage
        const char* type = reinterpret_cast<const char*>(&f[at + 4]);
        const uint8_t* data = &f[at + 8];
        if (std::memcmp(type, "iCCP", 4) == 0) {
            const void* nul = std::memchr(data, 0, std::min<size_t>(length, 80));
            if (!nul) damaged(path, "iCCP chunk without a profile name");
            const size_t name = size_t(static_cast<const uint8_t*>(nul) - data);
            if (name + 2 > length || data[name + 1] != 0) damaged(path, "unknown iCCP compression");
            return inflate_all(data + name + 2, length - name - 2, path);
        }
        if (std::memcmp(type, "IDAT", 4) == 0) break;  // iCCP must come before the image data
        at += 12 + length;
    }
    return {};
}

std::vector<uint8_t> from_jpeg(const std::vector<uint8_t>& f, const std::filesystem::path& path) {
    static const char kTag[] = "ICC_PROFILE";  // with its NUL: 12 bytes
    std::map<int, std::vector<uint8_t>> pieces;
    int count = 0;
    for (size_t at = 2; at + 4 <= f.size() && f[at] == 0xFF;) {
        const uint8_t marker = f[at + 1];
        if (marker == 0xDA || marker == 0xD9) break;  // start of scan / end of image
        const size_t length = size_t(f[at + 2]) << 8 | f[at + 3];
        if (length < 2 || at + 2 + length > f.size()) break;
        const uint8_t* data = &f[at + 4];
        const size_t size = length - 2;
        if (marker == 0xE2 && size > 14 && std::memcmp(data, kTag, 12) == 0) {
            const int seq = data[12], total = data[13];
            if (seq < 1 || seq > total || (count && total != count)) damaged(path, "APP2 sequence");
            count = total;
            pieces[seq].assign(data + 14, data + size);
        }
        at += 2 + length;
    }
    if (pieces.empty()) return {};
    if (int(pieces.size()) != count) damaged(path, "missing APP2 ICC segments");
    std::vector<uint8_t> out;
    for (auto& [seq, bytes] : pieces)
        out.insert(out.end(), bytes.begin(), bytes.end());
    return out;
}

std::vector<uint8_t> from_tiff(const std::filesystem::path& path) {
    // libtiff reports problems on stderr by default; the pixels' own decode reports damage.
    TIFFSetWarningHandler(nullptr);
    std::unique_ptr<TIFF, decltype(&TIFFClose)> tif(TIFFOpen(path.string().c_str(), "r"),
                                                    TIFFClose);
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
    if (f.size() >= 4 &&
        (std::memcmp(f.data(), "II*\0", 4) == 0 || std::memcmp(f.data(), "MM\0*", 4) == 0))
        return from_tiff(path);
    return parse_embedded_profile(f, path);
}

std::vector<uint8_t> parse_embedded_profile(const std::vector<uint8_t>& f,
                                            const std::filesystem::path& path) {
    if (f.size() >= 8 && std::memcmp(f.data(), "\x89PNG\r\n\x1a\n", 8) == 0)
        return from_png(f, path);
    if (f.size() >= 3 && f[0] == 0xFF && f[1] == 0xD8 && f[2] == 0xFF) return from_jpeg(f, path);
    return {};
}

}  // namespace tilejet::synth::detail
