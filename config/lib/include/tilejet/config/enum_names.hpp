#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace tilejet::config {

// How an enum is spelled wherever a person or a file names it: config keys, API fields, the
// job store's columns, CLI options. One table per enum, both ways, so a name and its parse can
// never disagree (they were written as switch, if-chain and table before, each slightly apart).
template <typename Enum, std::size_t N>
class EnumNames {
  public:
    using Entry = std::pair<Enum, std::string_view>;
    constexpr explicit EnumNames(std::array<Entry, N> entries) : entries_(entries) {}

    // The enum's name; "?" for a value outside the table (a cast from a corrupt integer).
    constexpr std::string_view name(Enum value) const {
        for (const auto& [e, text] : entries_)
            if (e == value) return text;
        return "?";
    }

    constexpr std::optional<Enum> parse(std::string_view text) const {
        for (const auto& [e, name] : entries_)
            if (name == text) return e;
        return std::nullopt;
    }

    // Every name in table order: the choices a config key or an error message lists.
    std::vector<std::string> names() const {
        std::vector<std::string> out;
        for (const auto& entry : entries_)
            out.emplace_back(entry.second);
        return out;
    }

    // The names as an error message lists them: "quilt, rsgf or enm".
    std::string choices() const {
        std::string out;
        for (std::size_t i = 0; i < N; ++i) {
            if (i > 0) out += i + 1 == N ? " or " : ", ";
            out += entries_[i].second;
        }
        return out;
    }

  private:
    std::array<Entry, N> entries_;
};

template <typename Enum, std::size_t N>
EnumNames(std::array<std::pair<Enum, std::string_view>, N>) -> EnumNames<Enum, N>;

}  // namespace tilejet::config
