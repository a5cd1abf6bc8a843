#pragma once

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <random>

#include "tilejet/quality/wall.hpp"

namespace tilejet::test {

// White RGB noise: no two windows of 16 px or more are ever equal.
inline cv::Mat noise_image(cv::Size size, uint32_t seed) {
    cv::Mat m(size, CV_8UC3);
    std::mt19937 rng(seed);
    for (int y = 0; y < m.rows; ++y)
        for (int x = 0; x < m.cols; ++x)
            m.at<cv::Vec3b>(y, x) = {uint8_t(rng()), uint8_t(rng()), uint8_t(rng())};
    return m;
}

inline quality::Wall wall_of(std::vector<cv::Mat> tiles, int columns) {
    quality::Wall w;
    w.tile = tiles.front().size();
    w.columns = columns;
    w.tiles = std::move(tiles);
    return w;
}

}  // namespace tilejet::test
