// The photo-eye debouncer on its own: timestamps in, confirmed levels out.

#include <catch2/catch.hpp>

#include "tilejet/drivers/debouncer.hpp"

using tilejet::drivers::Debouncer;
using namespace std::chrono_literals;
using ns = std::chrono::nanoseconds;

TEST_CASE("a level that holds is confirmed with the time of its first edge", "[drivers][gpio]") {
    Debouncer d(false, 2ms);
    d.edge(true, ns(10ms));
    CHECK_FALSE(d.confirm(ns(11ms)));
    CHECK(d.deadline() == ns(12ms));
    const auto c = d.confirm(ns(12ms));
    REQUIRE(c);
    CHECK(c->first == true);
    CHECK(c->second == ns(10ms));
    CHECK(d.stable());
    CHECK_FALSE(d.deadline());
}

TEST_CASE("a pulse shorter than the debounce time is dropped entirely", "[drivers][gpio]") {
    Debouncer d(false, 2ms);
    d.edge(true, ns(10ms));
    d.edge(false, ns(10ms) + 300us);
    CHECK_FALSE(d.confirm(ns(20ms)));
    CHECK_FALSE(d.stable());
    // The same on a dip while a tile covers the eye.
    Debouncer covered(true, 2ms);
    covered.edge(false, ns(5ms));
    covered.edge(true, ns(5ms) + 100us);
    CHECK_FALSE(covered.confirm(ns(50ms)));
    CHECK(covered.stable());
}

TEST_CASE("a pulse longer than the debounce time is two real edges", "[drivers][gpio]") {
    Debouncer d(false, 2ms);
    d.edge(true, ns(10ms));
    REQUIRE(d.confirm(ns(13ms)));
    d.edge(false, ns(14ms));
    const auto c = d.confirm(ns(16ms));
    REQUIRE(c);
    CHECK_FALSE(c->first);
}
