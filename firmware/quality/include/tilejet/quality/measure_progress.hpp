#pragma once

#include <cstddef>
#include <functional>
#include <string_view>

namespace tilejet::quality {

// Reports how far a quality measurement is: a stage name and done of total.
using MeasureProgress = std::function<void(std::string_view stage, size_t done, size_t total)>;

}  // namespace tilejet::quality
