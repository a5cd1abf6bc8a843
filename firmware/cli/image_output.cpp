#include "image_output.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "tilejet/colour/cmyk_tiff.hpp"

namespace tilejet::cli {

namespace {

void write_raw(const cv::Mat& image, const std::filesystem::path& path) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    const auto row_bytes = std::streamsize(size_t(image.cols) * image.elemSize());
    for (int r = 0; out && r < image.rows; ++r)
        out.write(reinterpret_cast<const char*>(image.ptr(r)), row_bytes);
    if (!out)
        throw std::runtime_error("cannot write '" + path.string() + "': " + std::strerror(errno));
}

}  // namespace

void write_rgb_image(const cv::Mat& rgb, const std::filesystem::path& path) {
    const std::string ext = path.extension().string();
    if (ext == ".raw") return write_raw(rgb, path);
    if (ext != ".png")
        throw std::runtime_error("output '" + path.string() + "': use a .png or .raw file name");
    cv::Mat bgr;
    cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
    bool ok = false;
    try {
        ok = cv::imwrite(path.string(), bgr);
    } catch (const cv::Exception& e) {
        throw std::runtime_error("cannot write '" + path.string() + "': " + e.what());
    }
    if (!ok) throw std::runtime_error("cannot write '" + path.string() + "'");
}

void write_cmyk_image(const cv::Mat& cmyk, const std::vector<uint8_t>& icc_profile,
                      const std::filesystem::path& path) {
    const std::string ext = path.extension().string();
    if (ext == ".raw") return write_raw(cmyk, path);
    if (ext != ".tif" && ext != ".tiff")
        throw std::runtime_error("output '" + path.string() +
                                 "': CMYK goes to a .tif or .raw file");
    colour::write_cmyk_tiff(cmyk, icc_profile, path);
}

}  // namespace tilejet::cli
