#include "tilejet/synth/internal/active_set.hpp"

#include <algorithm>
#include <bit>

#include "tilejet/synth/internal/mix64.hpp"

namespace tilejet::synth::detail {

uint64_t cell_key(uint64_t map_id, uint64_t seed, uint32_t cell_image, CellType type, int64_t i,
                  int64_t j) {
    uint64_t h = hash_combine(map_id, seed);
    h = hash_combine(h, (uint64_t(cell_image) << 1) | uint64_t(type));
    h = hash_combine(h, uint64_t(i));
    return hash_combine(h, uint64_t(j));
}

namespace {

// Any size of active set: degrees kept by counting.
void remove_overlaps_counting(const PatchSet& set, std::vector<uint16_t>& active) {
    const size_t n = active.size();
    std::vector<uint16_t> degree(n, 0);
    bool any = false;
    for (size_t a = 0; a < n; ++a) {
        for (size_t b = 0; b < n; ++b)
            degree[a] += uint16_t(a != b && set.overlaps(active[a], active[b]));
        any |= degree[a] != 0;
    }
    if (!any) return;

    std::vector<bool> dropped(n, false);
    for (;;) {
        size_t worst = n;
        for (size_t a = 0; a < n; ++a)
            if (!dropped[a] && degree[a] > 0 && (worst == n || degree[a] > degree[worst]))
                worst = a;
        if (worst == n) break;
        dropped[worst] = true;
        for (size_t b = 0; b < n; ++b)
            if (!dropped[b] && set.overlaps(active[worst], active[b])) --degree[b];
    }
    size_t kept = 0;
    for (size_t a = 0; a < n; ++a)
        if (!dropped[a]) active[kept++] = active[a];
    active.resize(kept);
}

}  // namespace

// Every cell of every tile comes through here (about ten active patches each), so the usual
// case keeps the overlaps among the active set as one 64-bit mask per patch: no allocation and
// no data-dependent branches while the masks are built.
void remove_overlaps(const PatchSet& set, std::vector<uint16_t>& active) {
    const size_t n = active.size();
    if (n < 2) return;
    if (n > 64) return remove_overlaps_counting(set, active);

    uint64_t with[64];  // with[a]: bit b set when active[a] and active[b] overlap
    int degree[64];     // overlaps of active[a] among the patches still kept
    bool any = false;
    for (size_t a = 0; a < n; ++a) {
        uint64_t bits = 0;
        int count = 0;
        for (size_t b = 0; b < n; ++b) {
            const uint64_t bit = uint64_t(a != b && set.overlaps(active[a], active[b]));
            bits |= bit << b;
            count += int(bit);
        }
        with[a] = bits;
        degree[a] = count;
        any |= count != 0;
    }
    if (!any) return;

    uint64_t kept = n == 64 ? ~uint64_t(0) : (uint64_t(1) << n) - 1;
    for (;;) {
        // The most overlaps among the patches still kept; ties go to the lower index.
        size_t worst = n;
        int most = 0;
        for (size_t a = 0; a < n; ++a)
            if (((kept >> a) & 1) && degree[a] > most) most = degree[a], worst = a;
        if (worst == n) break;
        kept &= ~(uint64_t(1) << worst);
        for (uint64_t left = with[worst] & kept; left != 0; left &= left - 1)
            --degree[std::countr_zero(left)];
    }
    size_t out = 0;
    for (size_t a = 0; a < n; ++a)
        if ((kept >> a) & 1) active[out++] = active[a];
    active.resize(out);
}

void activate(const PatchSet& set, uint64_t key, std::vector<uint16_t>& active) {
    active.clear();
    const uint64_t threshold = set.activation_threshold;
    const size_t n = set.size();
    uint64_t state = key;
    for (size_t k = 0; k < n; ++k) {
        state += kGolden;
        if (mix64(state) < threshold) active.push_back(uint16_t(k));
    }
}

}  // namespace tilejet::synth::detail
