#include "tilejet/config/toml_file.hpp"

#include <sstream>
#include <stdexcept>

namespace tilejet::config {

toml::table load_toml_file(const std::string& path) {
    try {
        return toml::parse_file(path);
    } catch (const toml::parse_error& e) {
        std::ostringstream s;
        s << path;
        if (e.source().begin.line)
            s << ':' << e.source().begin.line << ':' << e.source().begin.column;
        s << ": " << e.description();
        throw std::runtime_error(s.str());
    }
}

}  // namespace tilejet::config
