#include "tilejet/config/known_sections.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace tilejet::config {

void reject_unknown_sections(const toml::table& root, const std::vector<std::string_view>& known,
                             const ConfigSource& source) {
    for (const auto& [key, node] : root)
        if (std::find(known.begin(), known.end(), key.str()) == known.end())
            throw std::runtime_error(source.file + ":" + std::to_string(node.source().begin.line) +
                                     ": [" + std::string(key.str()) + "]: unknown section");
}

}  // namespace tilejet::config
