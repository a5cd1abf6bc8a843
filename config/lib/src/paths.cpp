#include "tilejet/config/paths.hpp"

#include <filesystem>

namespace tilejet::config {

std::string resolve_path(const ConfigSource& source, const std::string& path) {
    if (path.empty() || std::filesystem::path(path).is_absolute()) return path;
    return (std::filesystem::path(source.file).parent_path() / path).lexically_normal().string();
}

}  // namespace tilejet::config
