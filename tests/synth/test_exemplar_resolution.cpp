// A design's physical size: the exemplar's resolution read from each file format, resampling to
// the print resolution, and map build's errors when neither says what it is.

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zlib.h>

#include <catch2/catch.hpp>
#include <cstdlib>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "fixtures.hpp"
#include "profile_files.hpp"
#include "tilejet/synth/build.hpp"
#include "tilejet/synth/exemplar.hpp"
#include "tilejet/synth/lattice.hpp"
#include "tilejet/synth/map_file.hpp"

using namespace tilejet::synth;
using tilejet::test::TempDir;

namespace {

void write_all(const std::filesystem::path& p, const std::string& bytes) {
    std::ofstream(p, std::ios::binary) << bytes;
}

std::string be32(uint32_t v) {
    return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
}

// A PNG of `rgb` with `chunk_data` as a pHYs chunk (CRC and all) right after IHDR.
std::string png_with_phys(const cv::Mat& rgb, const std::string& chunk_data) {
    std::vector<uint8_t> png;
    cv::imencode(".png", rgb, png);
    std::string bytes(png.begin(), png.end());
    // 8 signature bytes, then IHDR: 4 length, 4 type, 13 data, 4 CRC.
    bytes.insert(8 + 25, tilejet::test::png_chunk("pHYs", chunk_data));
    return bytes;
}

std::string phys(uint32_t x_ppm, uint32_t y_ppm, uint8_t unit) {
    return be32(x_ppm) + be32(y_ppm) + std::string(1, char(unit));
}

// A JPEG of `rgb` whose JFIF segment says `unit` (0 aspect, 1 dpi, 2 dots per cm) and density.
std::string jpeg_with_jfif(const cv::Mat& rgb, uint8_t unit, uint16_t x, uint16_t y) {
    std::vector<uint8_t> jpg;
    cv::imencode(".jpg", rgb, jpg);
    std::string bytes(jpg.begin(), jpg.end());
    REQUIRE(bytes.substr(6, 5) == std::string("JFIF\0", 5));
    bytes[13] = char(unit);
    bytes[14] = char(x >> 8), bytes[15] = char(x);
    bytes[16] = char(y >> 8), bytes[17] = char(y);
    return bytes;
}

// Exif APP1 (big-endian TIFF structure) with XResolution = YResolution = num/den and unit,
// put right after SOI; the JFIF segment says aspect only.
std::string jpeg_with_exif(const cv::Mat& rgb, uint32_t num, uint32_t den, uint16_t unit,
                           size_t truncate_to = 0) {
    std::string tiff = "MM" + std::string("\0\x2a", 2) + be32(8);
    auto u16 = [](uint16_t v) { return std::string{char(v >> 8), char(v)}; };
    const uint32_t rational_at = 8 + 2 + 3 * 12 + 4;
    tiff += u16(3);
    tiff += u16(282) + u16(5) + be32(1) + be32(rational_at);
    tiff += u16(283) + u16(5) + be32(1) + be32(rational_at + 8);
    tiff += u16(296) + u16(3) + be32(1) + u16(unit) + u16(0);
    tiff += be32(0);
    tiff += be32(num) + be32(den) + be32(num) + be32(den);
    if (truncate_to) tiff.resize(truncate_to);
    const std::string payload = std::string("Exif\0\0", 6) + tiff;
    const std::string segment =
        std::string("\xFF\xE1", 2) + u16(uint16_t(payload.size() + 2)) + payload;
    std::string bytes = jpeg_with_jfif(rgb, 0, 1, 1);
    bytes.insert(2, segment);
    return bytes;
}

cv::Mat small_rgb() {
    cv::Mat rgb(40, 48, CV_8UC3);
    cv::randu(rgb, 0, 256);
    return rgb;
}

}  // namespace

TEST_CASE("the exemplar's resolution is read from PNG, JPEG (JFIF and Exif) and TIFF",
          "[exemplar][dpi]") {
    TempDir dir;
    const cv::Mat rgb = small_rgb();
    // PNG pHYs is in pixels per metre: 11811 is 300 dpi.
    write_all(dir / "a.png", png_with_phys(rgb, phys(11811, 11811, 1)));
    CHECK(read_exemplar_dpi(dir / "a.png").value() == Approx(300).epsilon(0.001));
    REQUIRE(cv::imread((dir / "a.png").string()).size() == rgb.size());  // still a good PNG
    write_all(dir / "aspect.png", png_with_phys(rgb, phys(1, 1, 0)));
    CHECK_FALSE(read_exemplar_dpi(dir / "aspect.png").has_value());
    cv::imwrite((dir / "none.png").string(), rgb);
    CHECK_FALSE(read_exemplar_dpi(dir / "none.png").has_value());

    write_all(dir / "a.jpg", jpeg_with_jfif(rgb, 1, 240, 240));
    CHECK(read_exemplar_dpi(dir / "a.jpg").value() == Approx(240));
    write_all(dir / "cm.jpg", jpeg_with_jfif(rgb, 2, 100, 100));
    CHECK(read_exemplar_dpi(dir / "cm.jpg").value() == Approx(254));
    write_all(dir / "aspect.jpg", jpeg_with_jfif(rgb, 0, 1, 1));
    CHECK_FALSE(read_exemplar_dpi(dir / "aspect.jpg").has_value());
    write_all(dir / "exif.jpg", jpeg_with_exif(rgb, 600, 1, 2));
    CHECK(read_exemplar_dpi(dir / "exif.jpg").value() == Approx(600));
    write_all(dir / "exif-cm.jpg", jpeg_with_exif(rgb, 400, 2, 3));
    CHECK(read_exemplar_dpi(dir / "exif-cm.jpg").value() == Approx(508));

    cv::Mat bgr;
    cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
    cv::imwrite(
        (dir / "a.tif").string(), bgr,
        {cv::IMWRITE_TIFF_RESUNIT, 2, cv::IMWRITE_TIFF_XDPI, 150, cv::IMWRITE_TIFF_YDPI, 150});
    CHECK(read_exemplar_dpi(dir / "a.tif").value() == Approx(150));
    cv::imwrite(
        (dir / "cm.tif").string(), bgr,
        {cv::IMWRITE_TIFF_RESUNIT, 3, cv::IMWRITE_TIFF_XDPI, 100, cv::IMWRITE_TIFF_YDPI, 100});
    CHECK(read_exemplar_dpi(dir / "cm.tif").value() == Approx(254));
}

TEST_CASE("damaged or non-square resolution records are errors naming the file",
          "[exemplar][dpi]") {
    TempDir dir;
    const cv::Mat rgb = small_rgb();
    auto error_of = [&](const std::string& name, const std::string& bytes) {
        write_all(dir / name, bytes);
        try {
            read_exemplar_dpi(dir / name);
        } catch (const SynthError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    std::string e = error_of("short.png", png_with_phys(rgb, std::string("\0\0\x2e", 3)));
    CHECK_THAT(e, Catch::Contains("short.png") && Catch::Contains("pHYs"));
    e = error_of("unit.png", png_with_phys(rgb, phys(11811, 11811, 7)));
    CHECK_THAT(e, Catch::Contains("unit.png") && Catch::Contains("unit"));
    e = error_of("zero.png", png_with_phys(rgb, phys(0, 0, 1)));
    CHECK_THAT(e, Catch::Contains("zero.png") && Catch::Contains("out of range"));
    e = error_of("tall.png", png_with_phys(rgb, phys(11811, 5905, 1)));
    CHECK_THAT(e, Catch::Contains("tall.png") && Catch::Contains("not square"));
    e = error_of("unit.jpg", jpeg_with_jfif(rgb, 9, 300, 300));
    CHECK_THAT(e, Catch::Contains("unit.jpg") && Catch::Contains("JFIF"));
    e = error_of("zero-den.jpg", jpeg_with_exif(rgb, 300, 0, 2));
    CHECK_THAT(e, Catch::Contains("zero-den.jpg") && Catch::Contains("denominator"));
    for (size_t cut : {4, 9, 30, 50}) {
        INFO("Exif cut to " << cut << " bytes");
        e = error_of("cut.jpg", jpeg_with_exif(rgb, 300, 1, 2, cut));
        CHECK_THAT(e, Catch::Contains("cut.jpg") && Catch::Contains("Exif"));
    }
}

TEST_CASE("a 300 dpi exemplar built for 360 dpi is 1.2 times larger, and so are its features",
          "[exemplar][dpi][build][heavy]") {
    // A mosaic of 25 px tiles at 300 dpi: at 360 dpi, 30 px tiles.
    const cv::Mat scanned =
        tilejet::test::make_lattice_texture({{25, 0}, {0, 25}}, {200, 200}, 3, true);
    const cv::Mat printed = resample_exemplar(scanned, 300, 360, "mosaic");
    CHECK(printed.size() == cv::Size(240, 240));
    BuildParams p;
    p.corner_colours = 2;
    p.patches = 8;
    p.candidates = 64;
    p.dpi = 360;
    p.exemplar_dpi = 300;
    const TextureMap map = build_texture_map(printed, p);
    CHECK(map.build.exemplar_width == 240);
    CHECK(map.build.dpi == 360);
    CHECK(map.build.exemplar_dpi == 300);
    const Lattice before = detect_lattice(scanned);
    const Lattice after = detect_lattice(render_region(map, 1, Region{0, 0, 480, 480}));
    INFO("before: v1 " << before.v1 << " v2 " << before.v2 << "; after: v1 " << after.v1 << " v2 "
                       << after.v2);
    REQUIRE(before.kind != LatticeKind::Stochastic);
    REQUIRE(after.kind != LatticeKind::Stochastic);
    CHECK(std::sqrt(double(after.area()) / before.area()) == Approx(1.2).epsilon(0.05));

    // The resolutions survive the file.
    TempDir dir;
    save_texture_map(map, dir / "m.tjmap");
    const TextureMap loaded = load_texture_map((dir / "m.tjmap").string());
    CHECK(loaded.build.dpi == 360);
    CHECK(loaded.build.exemplar_dpi == 300);
    CHECK(loaded.id == map.id);
}

namespace {

// Runs `attempt` in a child held to `limit_mb` of address space: 0 when it threw a SynthError
// whose message holds `expected`, 1 when it did not throw, 2 for another message, 4 for any
// other exception (it ran out of memory: it allocated first).
template <class F>
int in_memory_limit(size_t limit_mb, const std::string& expected, F attempt) {
    const pid_t child = fork();
    REQUIRE(child >= 0);
    if (child == 0) {
        // AddressSanitizer maps terabytes of shadow memory: under it no address-space limit
        // can hold, and the test checks the refusal and its message only.
#ifndef __SANITIZE_ADDRESS__
        const rlimit limit{limit_mb << 20, limit_mb << 20};
        setrlimit(RLIMIT_AS, &limit);
#else
        (void)limit_mb;
#endif
        int code = 1;
        try {
            attempt();
        } catch (const SynthError& e) {
            code = std::string(e.what()).find(expected) != std::string::npos ? 0 : 2;
        } catch (...) {
            code = 4;
        }
        _exit(code);
    }
    int status = 0;
    waitpid(child, &status, 0);
    REQUIRE(WIFEXITED(status));
    return WEXITSTATUS(status);
}

}  // namespace

TEST_CASE("an exemplar too large at the print resolution is refused before it is allocated",
          "[exemplar][dpi]") {
    // The refused result would need 3.2 GB.
    CHECK(in_memory_limit(600, "32768x32768", [] {
              const cv::Mat scan(2048, 2048, CV_8UC3, cv::Scalar(90, 90, 90));
              resample_exemplar(scan, 100, 1600, "slab.png");
          }) == 0);
}

TEST_CASE("an exemplar file too large to take is refused from its header, before decoding",
          "[exemplar]") {
    // A PNG whose header says 20000 x 20000 (1.2 GB of pixels), then a little image data.
    TempDir dir;
    std::vector<uint8_t> png;
    cv::imencode(".png", cv::Mat(16, 16, CV_8UC3, cv::Scalar(1, 2, 3)), png);
    std::string bytes(png.begin(), png.end());
    bytes.replace(16, 8, be32(20000) + be32(20000));
    const uint32_t crc = uint32_t(crc32(0, reinterpret_cast<const Bytef*>(&bytes[12]), 17));
    bytes.replace(29, 4, be32(crc));
    write_all(dir / "huge.png", bytes);
    REQUIRE(read_image_size(dir / "huge.png") == cv::Size(20000, 20000));
    const std::string path = (dir / "huge.png").string();
    CHECK(in_memory_limit(400, "20000x20000", [&] { load_exemplar(path, {}); }) == 0);
    // JPEG and TIFF headers give their sizes too.
    std::vector<uint8_t> jpg;
    cv::imencode(".jpg", cv::Mat(24, 40, CV_8UC3, cv::Scalar(1, 2, 3)), jpg);
    write_all(dir / "a.jpg", std::string(jpg.begin(), jpg.end()));
    CHECK(read_image_size(dir / "a.jpg") == cv::Size(40, 24));
    cv::imwrite((dir / "a.tif").string(), cv::Mat(24, 40, CV_8UC3, cv::Scalar(1, 2, 3)));
    CHECK(read_image_size(dir / "a.tif") == cv::Size(40, 24));
}

namespace {

std::string cli(const TempDir& dir, const std::string& args, int& status) {
    // Appended in place: GCC 12 takes the temporaries of a chain of + for overflows.
    std::string command = TILEJET_CLI;
    command.append(" ").append(args).append(" > ").append((dir / "log").string()).append(" 2>&1");
    status = std::system(command.c_str());
    return tilejet::test::read_file(dir / "log");
}

}  // namespace

TEST_CASE("map build needs the exemplar's resolution and records the design's size",
          "[exemplar][dpi][cli]") {
    TempDir dir;
    const cv::Mat rgb = tilejet::test::make_lattice_texture({{25, 0}, {0, 25}}, {160, 160}, 2);
    cv::Mat bgr;
    cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
    const std::string plain = (dir / "plain.png").string();
    cv::imwrite(plain, bgr);
    const std::string small = " --cell 32 --corner-colours 2 --patches 8 --candidates 32";
    int status = 0;
    std::string out = cli(dir, "map build " + plain + " --dpi 360 -o m.tjmap" + small, status);
    CHECK(status != 0);
    CHECK_THAT(out, Catch::Contains("plain.png") && Catch::Contains("--exemplar-dpi"));

    // A file that records 300 dpi, built for 360: 1.2 times larger, and map info says so.
    const std::string scanned = (dir / "scanned.png").string();
    write_all(scanned, png_with_phys(bgr, phys(11811, 11811, 1)));
    const std::string map = (dir / "m.tjmap").string();
    out = cli(dir, "map build " + scanned + " --dpi 360 -o " + map + small, status);
    INFO(out);
    REQUIRE(status == 0);
    out = cli(dir, "map info " + map, status);
    REQUIRE(status == 0);
    CHECK_THAT(out, Catch::Contains("\"dpi\":360") && Catch::Contains("\"exemplar_dpi\":300"));
    CHECK_THAT(out, Catch::Contains("\"exemplar_width\":192"));
    // 192 px at 360 dpi is 13.55 mm.
    CHECK_THAT(out, Catch::Contains("\"exemplar_mm\":[13.54"));
}

TEST_CASE("the default cell holds the stone's largest structures: fine grain, small cells",
          "[exemplar][build][cell][heavy]") {
    // Noise blurred to grains of a few pixels and to blotches of about 70 px.
    cv::Mat noise(320, 320, CV_8UC3), fine, coarse;
    cv::randu(noise, 0, 256);
    cv::GaussianBlur(noise, fine, {0, 0}, 1.0);
    cv::GaussianBlur(noise, coarse, {0, 0}, 28.0);
    cv::normalize(coarse, coarse, 0, 255, cv::NORM_MINMAX);
    BuildParams p;
    p.corner_colours = 2;
    p.patches = 8;
    p.candidates = 32;
    const TextureMap f = build_texture_map(fine, p), c = build_texture_map(coarse, p);
    INFO("fine: grain " << f.build.grain << " px, cell " << f.cell_width << "; coarse: grain "
                        << c.build.grain << " px, cell " << c.cell_width);
    CHECK(f.build.grain > 0);
    CHECK(c.build.grain > 4 * f.build.grain);
    CHECK(f.cell_width < c.cell_width);
    CHECK(f.cell_width == f.cell_height);
    // --cell still decides when given, and says so.
    p.cell_size = 48;
    const TextureMap given = build_texture_map(coarse, p);
    CHECK(given.cell_width == 48);
    CHECK(given.build.grain == 0);
}
