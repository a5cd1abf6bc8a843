// The head mirror's arithmetic (firmware/daemon/head_mirror.hpp), on its own: no clock, no
// line, no store. A resync is checked against a model of the heads as a FIFO for every small
// case: how many tiles were sent, whether the last was mid-send, and how many the heads printed.
#include <catch2/catch.hpp>

#include "head_mirror.hpp"

using namespace tilejet;
using daemon::HeadEntry;
using daemon::HeadMirror;

namespace {

std::vector<jobs::QueuedTile> queued(int sent, bool last_sending) {
    std::vector<jobs::QueuedTile> q;
    for (int i = 0; i < sent; ++i)
        q.push_back(
            {7, 100 + i,
             last_sending && i == sent - 1 ? jobs::TileState::sending : jobs::TileState::sent,
             i + 1});
    return q;
}

std::vector<std::int64_t> indices(const std::vector<HeadEntry>& entries) {
    std::vector<std::int64_t> out;
    for (const HeadEntry& e : entries)
        out.push_back(e.index);
    return out;
}

}  // namespace

TEST_CASE("a resync finds which sent tiles were printed, for every small case",
          "[daemon][mirror]") {
    for (int sent = 0; sent <= 5; ++sent)
        for (bool last_sending : {false, true}) {
            if (sent == 0 && last_sending) continue;
            // What really happened: the last tile, if mid-send, reached the heads or not; then
            // the line printed the oldest `printed` of those that reached them; `strangers`
            // tiles the store never knew were in the heads before all of them.
            for (bool reached : {true, false}) {
                if (!last_sending && !reached) continue;
                const int in_heads_ever = sent - (reached ? 0 : 1);
                for (int printed = 0; printed <= in_heads_ever; ++printed)
                    for (int strangers = 0; strangers <= (printed == 0 ? 2 : 0); ++strangers) {
                        const int held = in_heads_ever - printed + strangers;
                        INFO("sent " << sent << (last_sending ? " (last mid-send)" : "")
                                     << (reached ? " reached" : " lost") << ", printed " << printed
                                     << ", strangers " << strangers);
                        const auto plan = HeadMirror::plan_resync(queued(sent, last_sending), held);
                        CHECK(plan.last_sending_reached.has_value() == last_sending);
                        // With the last tile mid-send, one fewer held reads as that tile lost,
                        // not as one more printed: rule 2 (no arrival during a send) makes
                        // that the only way it can happen, so only then is the plan exact.
                        if (!last_sending || (printed == 0 && strangers == 0)) {
                            if (last_sending) CHECK(*plan.last_sending_reached == reached);
                            CHECK(plan.unknown == strangers);
                            std::vector<std::int64_t> want_printed, want_held;
                            for (int i = 0; i < in_heads_ever; ++i)
                                (i < printed ? want_printed : want_held).push_back(100 + i);
                            CHECK(indices(plan.printed) == want_printed);
                            CHECK(indices(plan.held) == want_held);
                        }
                        // Whatever the case: every tile is printed, held or dropped, once.
                        const size_t accounted =
                            plan.printed.size() + plan.held.size() +
                            (plan.last_sending_reached && !*plan.last_sending_reached ? 1 : 0);
                        CHECK(accounted == size_t(sent));
                        CHECK(int(plan.held.size()) + plan.unknown == held);
                    }
            }
        }
}

TEST_CASE("after a resync the mirror is the strangers, the held tiles, then the probes",
          "[daemon][mirror]") {
    HeadMirror m;
    CHECK_FALSE(m.certain());
    // Two sent, three held: one the store never saw, older than both.
    const auto plan2 = HeadMirror::plan_resync(queued(2, false), 3);
    REQUIRE(plan2.unknown == 1);
    m.adopt(plan2, {{7, 102, true}, {7, -5, true}});
    CHECK(m.certain());
    REQUIRE(m.size() == 5);
    const auto first = m.arrived();
    REQUIRE(first);
    CHECK_FALSE(first->known);  // the stranger passes as a blank
    CHECK(m.arrived()->index == 100);
    CHECK(m.holds_tiles_of(7));
    CHECK_FALSE(m.holds_tiles_of(8));
    CHECK(m.arrived()->index == 101);
    CHECK(m.arrived()->index == 102);
    CHECK(m.holds_tiles_of(7) == false);  // only the blank probe is left
    CHECK_FALSE(m.holds_tiles());
    CHECK(m.arrived()->index == -5);
    CHECK_FALSE(m.arrived().has_value());  // an arrival with nothing in the heads
}

TEST_CASE("heads that restart lose the oldest entries, doubt holds until a resync",
          "[daemon][mirror]") {
    HeadMirror m;
    m.known_empty();
    CHECK(m.certain());
    for (int i = 0; i < 4; ++i)
        m.sent({3, i, true});
    const auto lost = m.lose_oldest(3);
    CHECK(indices(lost) == std::vector<std::int64_t>{0, 1, 2});
    CHECK(m.size() == 1);
    CHECK(m.lose_oldest(5).size() == 1);  // never more than it holds
    m.doubt();
    CHECK_FALSE(m.certain());
    m.sent({3, 9, true});
    CHECK_FALSE(m.certain());  // a send does not restore trust
    m.forget();
    CHECK(m.empty());
    CHECK_FALSE(m.certain());
}
