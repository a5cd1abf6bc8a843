#include "arguments.hpp"

#include <charconv>
#include <stdexcept>

namespace tilejet::cli {

namespace {

template <typename T>
bool parse_int(std::string_view s, T& out) {
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return ec == std::errc() && end == s.data() + s.size() && !s.empty();
}

[[noreturn]] void bad(std::string_view option, std::string_view text, std::string_view expected) {
    throw std::invalid_argument(std::string(option) + " '" + std::string(text) + "': expected " +
                                std::string(expected));
}

}  // namespace

Point2 parse_point(std::string_view text, std::string_view option) {
    constexpr int64_t kLimit = int64_t(1) << 40;
    const size_t comma = text.find(',');
    Point2 p;
    if (comma == std::string_view::npos || !parse_int(text.substr(0, comma), p.x) ||
        !parse_int(text.substr(comma + 1), p.y))
        bad(option, text, "X,Y with integer coordinates");
    if (p.x < -kLimit || p.x > kLimit || p.y < -kLimit || p.y > kLimit)
        bad(option, text, "coordinates within +-2^40");
    return p;
}

Size2 parse_size(std::string_view text, std::string_view option) {
    const size_t x = text.find('x');
    Size2 s;
    if (x == std::string_view::npos || !parse_int(text.substr(0, x), s.width) ||
        !parse_int(text.substr(x + 1), s.height))
        bad(option, text, "WxH in pixels, e.g. 1200x600");
    if (s.width < 1 || s.height < 1 || s.width > 65536 || s.height > 65536)
        bad(option, text, "each side between 1 and 65536 px");
    return s;
}

}  // namespace tilejet::cli
