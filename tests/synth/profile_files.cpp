#include "profile_files.hpp"

#include <zlib.h>

#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace tilejet::test {

std::string file_text(const char* path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

namespace {

void put_be32(std::string& s, uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8)
        s += char((v >> shift) & 0xFF);
}

}  // namespace

std::string png_chunk(const std::string& type, const std::string& data) {
    const std::string body = type + data;
    std::string chunk;
    put_be32(chunk, uint32_t(data.size()));
    chunk += body;
    put_be32(chunk,
             uint32_t(crc32(0, reinterpret_cast<const Bytef*>(body.data()), uInt(body.size()))));
    return chunk;
}

std::string png_with_profile(const cv::Mat& rgb, const std::string& icc, bool break_zlib) {
    cv::Mat bgr;
    cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
    std::vector<uchar> png;
    cv::imencode(".png", bgr, png);
    uLongf len = compressBound(uLong(icc.size()));
    std::string z(len, '\0');
    compress2(reinterpret_cast<Bytef*>(z.data()), &len, reinterpret_cast<const Bytef*>(icc.data()),
              uLong(icc.size()), 9);
    z.resize(len);
    if (break_zlib) z[z.size() / 2] = char(z[z.size() / 2] ^ 0x55), z.resize(z.size() - 4);
    std::string out(png.begin(), png.end());
    out.insert(33, png_chunk("iCCP", std::string("Adobe RGB") + '\0' + '\0' +
                                         z));  // 8-byte signature + IHDR (4 + 4 + 13 + 4)
    return out;
}

std::string jpeg_with_profile(const cv::Mat& rgb, const std::string& icc) {
    cv::Mat bgr;
    cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
    std::vector<uchar> jpg;
    cv::imencode(".jpg", bgr, jpg, {cv::IMWRITE_JPEG_QUALITY, 95});
    std::string segment = "\xFF\xE2";
    const size_t length = 2 + 12 + 2 + icc.size();
    segment += char(length >> 8), segment += char(length & 0xFF);
    segment += std::string("ICC_PROFILE") + '\0' + char(1) + char(1) + icc;
    std::string out(jpg.begin(), jpg.end());
    out.insert(2, segment);
    return out;
}

cv::Mat saturated_swatches() {
    cv::Mat rgb(32, 32, CV_8UC3);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x)
            rgb.at<cv::Vec3b>(y, x) = {uint8_t(x * 8), uint8_t(200 - y * 4), uint8_t(40 + x * 4)};
    return rgb;
}

}  // namespace tilejet::test
