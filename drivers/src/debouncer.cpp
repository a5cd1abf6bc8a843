#include "tilejet/drivers/debouncer.hpp"

namespace tilejet::drivers {

void Debouncer::edge(bool level, ns at) {
    if (pending_) {
        if (level == stable_) pending_.reset();  // back before it held: a glitch
        return;                                  // (level == pending: a repeated edge)
    }
    if (level != stable_) pending_.emplace(level, at);
}

std::optional<std::pair<bool, Debouncer::ns>> Debouncer::confirm(ns now) {
    if (!pending_ || now - pending_->second < hold_) return std::nullopt;
    auto confirmed = *pending_;
    stable_ = confirmed.first;
    pending_.reset();
    return confirmed;
}

std::optional<Debouncer::ns> Debouncer::deadline() const {
    if (!pending_) return std::nullopt;
    return pending_->second + hold_;
}

}  // namespace tilejet::drivers
