#include "image_output.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace tilejet::cli {

void write_rgb_image(const cv::Mat& rgb, const std::filesystem::path& path) {
    const std::string ext = path.extension().string();
    if (ext == ".raw") {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        for (int r = 0; out && r < rgb.rows; ++r)
            out.write(reinterpret_cast<const char*>(rgb.ptr(r)), std::streamsize(rgb.cols) * 3);
        if (!out)
            throw std::runtime_error("cannot write '" + path.string() +
                                     "': " + std::strerror(errno));
        return;
    }
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

}  // namespace tilejet::cli
