#pragma once

// The containers of the image formats exemplars come in, walked for what OpenCV does not return
// (embedded ICC profiles, resolutions, sizes from the header): PNG chunks before the image
// data, JPEG segments before the scan, TIFF tags through libtiff.

#include <tiffio.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string_view>
#include <vector>

namespace tilejet::synth::detail {

inline uint32_t be32(const uint8_t* p) {
    return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | uint32_t(p[3]);
}

inline bool is_png(const std::vector<uint8_t>& f) {
    return f.size() >= 8 && std::memcmp(f.data(), "\x89PNG\r\n\x1a\n", 8) == 0;
}
inline bool is_jpeg(const std::vector<uint8_t>& f) {
    return f.size() >= 3 && f[0] == 0xFF && f[1] == 0xD8 && f[2] == 0xFF;
}
inline bool is_tiff(const std::vector<uint8_t>& f) {
    return f.size() >= 4 &&
           (std::memcmp(f.data(), "II*\0", 4) == 0 || std::memcmp(f.data(), "MM\0*", 4) == 0);
}

// Calls visit(type, data, length) for each chunk of the PNG `f` before its image data, in
// order, until visit returns true. A truncated chunk ends the walk: OpenCV reports the damage
// when it decodes the pixels.
template <class Visit>
void for_each_png_chunk(const std::vector<uint8_t>& f, Visit visit) {
    for (size_t at = 8; at + 12 <= f.size();) {
        const uint32_t length = be32(&f[at]);
        if (length > f.size() - at - 12) return;
        const std::string_view type(reinterpret_cast<const char*>(&f[at + 4]), 4);
        if (type == "IDAT") return;  // metadata chunks come before the image data
        if (visit(type, &f[at + 8], size_t(length))) return;
        at += 12 + length;
    }
}

// Calls visit(marker, data, size) for each segment of the JPEG `f` before its scan, in order,
// until visit returns true. A truncated segment ends the walk, as above.
template <class Visit>
void for_each_jpeg_segment(const std::vector<uint8_t>& f, Visit visit) {
    for (size_t at = 2; at + 4 <= f.size() && f[at] == 0xFF;) {
        const uint8_t marker = f[at + 1];
        if (marker == 0xDA || marker == 0xD9) return;  // start of scan / end of image
        const size_t length = size_t(f[at + 2]) << 8 | f[at + 3];
        if (length < 2 || at + 2 + length > f.size()) return;
        if (visit(marker, &f[at + 4], length - 2)) return;
        at += 2 + length;
    }
}

using TiffFile = std::unique_ptr<TIFF, decltype(&TIFFClose)>;

// Opens a TIFF to read its tags; null when libtiff cannot. Quietly: libtiff reports problems
// on stderr by default, and the pixels' own decode reports damage.
inline TiffFile open_tiff(const std::filesystem::path& path) {
    TIFFSetWarningHandler(nullptr);
    return TiffFile(TIFFOpen(path.string().c_str(), "r"), TIFFClose);
}

}  // namespace tilejet::synth::detail
