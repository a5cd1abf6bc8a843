#include "active_set.hpp"

#include <algorithm>

#include "mix64.hpp"

namespace tilejet::synth::detail {

uint64_t cell_key(uint64_t map_id, uint64_t seed, uint32_t cell_image, CellType type, int64_t i,
                  int64_t j) {
    uint64_t h = hash_combine(map_id, seed);
    h = hash_combine(h, (uint64_t(cell_image) << 1) | uint64_t(type));
    h = hash_combine(h, uint64_t(i));
    return hash_combine(h, uint64_t(j));
}

// Active sets are small (about 10 patches), so a quadratic pass over the overlap bit matrix is
// the fastest way.
void remove_overlaps(const PatchSet& set, std::vector<uint16_t>& active) {
    const size_t n = active.size();
    if (n < 2) return;
    uint16_t degree_storage[64];
    std::vector<uint16_t> degree_heap;
    uint16_t* degree = degree_storage;
    if (n > 64) degree_heap.resize(n), degree = degree_heap.data();

    bool any = false;
    for (size_t a = 0; a < n; ++a) {
        degree[a] = 0;
        for (size_t b = 0; b < n; ++b)
            if (a != b && set.overlaps(active[a], active[b])) ++degree[a];
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
