#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace tilejet::cli {

struct Point2 {
    int64_t x = 0, y = 0;
};
struct Size2 {
    int width = 0, height = 0;
};

// "X,Y" with integers anywhere in [-2^40, 2^40]. Throws std::invalid_argument naming `option`.
Point2 parse_point(std::string_view text, std::string_view option);
// "WxH" with 1 <= W, H <= 65536.
Size2 parse_size(std::string_view text, std::string_view option);

}  // namespace tilejet::cli
