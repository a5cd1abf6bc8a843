// Where image files record their resolution: PNG's pHYs chunk, JPEG's JFIF APP0 segment or the
// Exif APP1 segment's first image directory, TIFF's XResolution and ResolutionUnit tags.

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "image_containers.hpp"
#include "tilejet/synth/exemplar.hpp"

namespace tilejet::synth {

namespace {

using namespace detail;

constexpr double kMmPerInch = 25.4;

[[noreturn]] void damaged_resolution(const std::filesystem::path& path, const std::string& why) {
    throw SynthError("exemplar '" + path.string() + "': its resolution record is damaged (" + why +
                     "); give the resolution with --exemplar-dpi");
}

// One resolution from a horizontal and a vertical one (in pixels per inch).
std::optional<double> square(double x, double y, const std::filesystem::path& path) {
    if (!std::isfinite(x) || !std::isfinite(y) || x < kMinDpi || y < kMinDpi || x > kMaxDpi ||
        y > kMaxDpi)
        damaged_resolution(path, "resolution " + std::to_string(x) + " x " + std::to_string(y) +
                                     " ppi is out of range");
    if (std::abs(x - y) > 0.01 * std::max(x, y))
        throw SynthError("exemplar '" + path.string() + "' has pixels that are not square (" +
                         std::to_string(x) + " x " + std::to_string(y) +
                         " ppi): resample it to square pixels first");
    return (x + y) / 2;
}

std::optional<double> resolution_from_png(const std::vector<uint8_t>& f,
                                          const std::filesystem::path& path) {
    std::optional<double> dpi;
    for_each_png_chunk(f, [&](std::string_view type, const uint8_t* d, size_t length) {
        if (type != "pHYs") return false;
        if (length != 9)
            damaged_resolution(path, "pHYs chunk of " + std::to_string(length) + " bytes");
        if (d[8] == 0) return true;  // an aspect ratio only
        if (d[8] != 1) damaged_resolution(path, "pHYs unit " + std::to_string(d[8]));
        // Pixels per metre, whole: 300 dpi is stored as 11811 and reads 299.9994. A hundredth
        // of a dpi is far below what the metre's rounding can say.
        auto per_inch = [](uint32_t ppm) { return std::round(ppm * kMmPerInch / 10) / 100; };
        dpi = square(per_inch(be32(d)), per_inch(be32(d + 4)), path);
        return true;
    });
    return dpi;
}

// Exif: a TIFF structure after "Exif\0\0"; XResolution (282, RATIONAL) and ResolutionUnit (296,
// SHORT: 2 inch, the default, 3 cm) in the first image directory.
std::optional<double> from_exif(const uint8_t* d, size_t size, const std::filesystem::path& path) {
    if (size < 8) damaged_resolution(path, "Exif header");
    const bool little = d[0] == 'I' && d[1] == 'I';
    if (!little && !(d[0] == 'M' && d[1] == 'M')) damaged_resolution(path, "Exif byte order");
    auto u16 = [&](size_t at) -> uint32_t {
        if (at + 2 > size) damaged_resolution(path, "Exif directory runs past its segment");
        return little ? uint32_t(d[at]) | uint32_t(d[at + 1]) << 8
                      : uint32_t(d[at]) << 8 | uint32_t(d[at + 1]);
    };
    auto u32 = [&](size_t at) -> uint32_t {
        return little ? u16(at) | u16(at + 2) << 16 : u16(at) << 16 | u16(at + 2);
    };
    const size_t ifd = u32(4);
    const uint32_t entries = u16(ifd);
    std::optional<double> x, y;
    double unit = 1;  // inches per unit
    for (uint32_t i = 0; i < entries; ++i) {
        const size_t e = ifd + 2 + size_t(i) * 12;
        const uint32_t tag = u16(e), type = u16(e + 2);
        if (tag == 282 || tag == 283) {
            if (type != 5) damaged_resolution(path, "Exif resolution is not a rational");
            const size_t at = u32(e + 8);
            const double den = u32(at + 4);
            if (den == 0) damaged_resolution(path, "Exif resolution with a zero denominator");
            (tag == 282 ? x : y) = u32(at) / den;
        } else if (tag == 296) {
            const uint32_t u = u16(e + 8);
            if (u == 1) return std::nullopt;  // no absolute unit
            if (u != 2 && u != 3)
                damaged_resolution(path, "Exif resolution unit " + std::to_string(u));
            unit = u == 3 ? 1 / 2.54 : 1;
        }
    }
    if (!x) return std::nullopt;
    return square(*x / unit, (y ? *y : *x) / unit, path);
}

std::optional<double> resolution_from_jpeg(const std::vector<uint8_t>& f,
                                           const std::filesystem::path& path) {
    std::optional<double> jfif, exif;
    for_each_jpeg_segment(f, [&](uint8_t marker, const uint8_t* d, size_t size) {
        if (marker == 0xE0 && size >= 12 && std::memcmp(d, "JFIF\0", 5) == 0) {
            const int unit = d[7];
            const double x = double(d[8] << 8 | d[9]), y = double(d[10] << 8 | d[11]);
            // Unit 0 is an aspect ratio: what JFIF writers put when they know no resolution.
            if (unit == 1) jfif = square(x, y, path);
            if (unit == 2) jfif = square(x * 2.54, y * 2.54, path);
            if (unit > 2) damaged_resolution(path, "JFIF density unit " + std::to_string(unit));
            if (jfif) return true;
        }
        if (marker == 0xE1 && size >= 6 && std::memcmp(d, "Exif\0\0", 6) == 0 && !exif)
            exif = from_exif(d + 6, size - 6, path);
        return false;
    });
    return jfif ? jfif : exif;
}

std::optional<double> resolution_from_tiff(const std::filesystem::path& path) {
    const TiffFile tif = open_tiff(path);
    if (!tif) return std::nullopt;
    float x = 0, y = 0;
    uint16_t unit = RESUNIT_INCH;
    if (!TIFFGetField(tif.get(), TIFFTAG_XRESOLUTION, &x)) return std::nullopt;
    if (!TIFFGetField(tif.get(), TIFFTAG_YRESOLUTION, &y)) y = x;
    TIFFGetFieldDefaulted(tif.get(), TIFFTAG_RESOLUTIONUNIT, &unit);
    if (unit == RESUNIT_NONE) return std::nullopt;
    const double per_inch = unit == RESUNIT_CENTIMETER ? 2.54 : 1;
    return square(x * per_inch, y * per_inch, path);
}

// Width and height as a PNG's IHDR, a JPEG's start-of-frame or a TIFF's tags give them.
std::optional<cv::Size> png_size(const std::vector<uint8_t>& f) {
    if (f.size() < 24 || std::memcmp(&f[12], "IHDR", 4) != 0) return std::nullopt;
    return cv::Size(int(std::min<uint32_t>(be32(&f[16]), INT32_MAX)),
                    int(std::min<uint32_t>(be32(&f[20]), INT32_MAX)));
}

std::optional<cv::Size> jpeg_size(const std::vector<uint8_t>& f) {
    std::optional<cv::Size> size;
    for_each_jpeg_segment(f, [&](uint8_t marker, const uint8_t* d, size_t length) {
        // SOF0..SOF15 but DHT (C4), JPG (C8) and DAC (CC): precision, height, width.
        if (marker < 0xC0 || marker > 0xCF || marker == 0xC4 || marker == 0xC8 || marker == 0xCC ||
            length < 5)
            return false;
        size = cv::Size(int(d[3]) << 8 | d[4], int(d[1]) << 8 | d[2]);
        return true;
    });
    return size;
}

std::optional<cv::Size> tiff_size(const std::filesystem::path& path) {
    const TiffFile tif = open_tiff(path);
    uint32_t w = 0, h = 0;
    if (!tif || !TIFFGetField(tif.get(), TIFFTAG_IMAGEWIDTH, &w) ||
        !TIFFGetField(tif.get(), TIFFTAG_IMAGELENGTH, &h))
        return std::nullopt;
    return cv::Size(int(std::min<uint32_t>(w, INT32_MAX)), int(std::min<uint32_t>(h, INT32_MAX)));
}

// The first megabyte of a file: where every format keeps its size and resolution.
std::vector<uint8_t> file_head(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw SynthError("cannot read exemplar '" + path.string() + "'");
    std::vector<uint8_t> f(1u << 20);
    in.read(reinterpret_cast<char*>(f.data()), std::streamsize(f.size()));
    f.resize(size_t(in.gcount()));
    return f;
}

}  // namespace

std::optional<cv::Size> read_image_size(const std::filesystem::path& path) {
    const std::vector<uint8_t> f = file_head(path);
    if (is_tiff(f)) return tiff_size(path);
    if (is_png(f)) return png_size(f);
    if (is_jpeg(f)) return jpeg_size(f);
    return std::nullopt;
}

std::optional<double> read_exemplar_dpi(const std::filesystem::path& path) {
    const std::vector<uint8_t> f = file_head(path);
    if (is_tiff(f)) return resolution_from_tiff(path);
    if (is_png(f)) return resolution_from_png(f, path);
    if (is_jpeg(f)) return resolution_from_jpeg(f, path);
    return std::nullopt;
}

cv::Mat resample_exemplar(const cv::Mat& rgb, double from_dpi, double to_dpi,
                          const std::string& name) {
    if (!(from_dpi > 0) || !(to_dpi > 0) || !std::isfinite(from_dpi) || !std::isfinite(to_dpi))
        throw SynthError("exemplar '" + name + "': resolutions must be positive");
    const double scale = to_dpi / from_dpi;
    const double w = std::round(rgb.cols * scale), h = std::round(rgb.rows * scale);
    // Checked before anything is allocated: a 300 dpi scan printed at 2400 dpi is 64 times the
    // pixels.
    if (w * h > double(kMaxExemplarPixels) || w < kMinExemplarSide || h < kMinExemplarSide)
        throw SynthError("exemplar '" + name + "' at " + std::to_string(from_dpi) + " dpi is " +
                         std::to_string(int64_t(w)) + "x" + std::to_string(int64_t(h)) + " px at " +
                         std::to_string(to_dpi) + " dpi; texture maps take " +
                         std::to_string(kMinExemplarSide) + " px a side up to " +
                         std::to_string(kMaxExemplarPixels >> 20) +
                         " Mpx: crop it, or build for a lower --dpi");
    if (w == rgb.cols && h == rgb.rows) return rgb.clone();
    cv::Mat out;
    // Area averaging when shrinking (no aliasing of fine grain), Lanczos when enlarging.
    cv::resize(rgb, out, cv::Size(int(w), int(h)), 0, 0,
               scale < 1 ? cv::INTER_AREA : cv::INTER_LANCZOS4);
    return out;
}

}  // namespace tilejet::synth
