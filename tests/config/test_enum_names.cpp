#include <catch2/catch.hpp>

#include "tilejet/config/enum_names.hpp"

namespace {

enum class Valve { closed, open, stuck };

constexpr tilejet::config::EnumNames kValves{std::array<std::pair<Valve, std::string_view>, 3>{{
    {Valve::closed, "closed"},
    {Valve::open, "open"},
    {Valve::stuck, "stuck"},
}}};

}  // namespace

TEST_CASE("an enum's names read both ways from one table", "[enum_names]") {
    for (Valve v : {Valve::closed, Valve::open, Valve::stuck})
        REQUIRE(kValves.parse(kValves.name(v)) == v);
    CHECK(kValves.name(Valve::stuck) == "stuck");
    CHECK(kValves.parse("open") == Valve::open);
    CHECK(kValves.names() == std::vector<std::string>{"closed", "open", "stuck"});
    static_assert(kValves.parse("closed") == Valve::closed, "usable at compile time");
}

TEST_CASE("a name not in the table, or a value outside it, is said so", "[enum_names]") {
    CHECK_FALSE(kValves.parse("Open").has_value());  // names are exact: a config typo is an error
    CHECK_FALSE(kValves.parse("").has_value());
    CHECK_FALSE(kValves.parse("open ").has_value());
    CHECK(kValves.name(static_cast<Valve>(7)) == "?");  // a corrupt integer cast to the enum
}

TEST_CASE("an error message lists an enum's names in table order", "[enum_names]") {
    CHECK(kValves.choices() == "closed, open or stuck");
    constexpr tilejet::config::EnumNames two{std::array<std::pair<Valve, std::string_view>, 2>{{
        {Valve::open, "open"},
        {Valve::closed, "shut"},
    }}};
    CHECK(two.choices() == "open or shut");
    constexpr tilejet::config::EnumNames one{
        std::array<std::pair<Valve, std::string_view>, 1>{{{Valve::stuck, "stuck"}}}};
    CHECK(one.choices() == "stuck");
}
