#pragma once

#include <chrono>
#include <optional>

// Debouncer: confirms an input level only once it has held for the debounce time. A photo-eye
// sees glitches (a splash of glaze, a reflection, a cable picking up the inverter) far shorter
// than any real tile; without this each would be counted as a tile and shift every following
// print by one tile.
namespace tilejet::drivers {

class Debouncer {
  public:
    using ns = std::chrono::nanoseconds;

    Debouncer(bool level, ns hold) : stable_(level), hold_(hold) {}

    // A raw edge to `level` at `at`. An edge back to the stable level before the pending one
    // was confirmed cancels both (a glitch).
    void edge(bool level, ns at);
    // The level confirmed by `now`, with the time of the raw edge that started it; at most one
    // per call.
    std::optional<std::pair<bool, ns>> confirm(ns now);
    // When confirm() next has something to say, if anything is pending.
    std::optional<ns> deadline() const;
    bool stable() const { return stable_; }

  private:
    bool stable_;
    ns hold_;
    std::optional<std::pair<bool, ns>> pending_;
};

}  // namespace tilejet::drivers
