#pragma once

// The operator panel's files (firmware/panel/), compiled into the binary by
// firmware/panel/embed.cmake.
#include <string_view>
#include <vector>

namespace tilejet::api {

struct PanelAsset {
    std::string_view name;  // "index.html"
    std::string_view content_type;
    std::string_view body;
};

const std::vector<PanelAsset>& panel_assets();

}  // namespace tilejet::api
