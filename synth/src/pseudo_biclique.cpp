#include "pseudo_biclique.hpp"

#include <algorithm>

namespace tilejet::synth::detail {

BicliqueSplit split_pseudo_biclique(size_t n, const std::vector<uint8_t>& conflict, Rng& rng) {
    BicliqueSplit split;
    if (n < 2) return split;
    auto conflicts = [&](size_t u, size_t v) { return bool(conflict[u * n + v]); };

    // Seed pair: a random patch and the first patch after it (cyclically) it can live with.
    size_t seed_a = n, seed_b = n;
    const size_t start = size_t(rng.below(n));
    for (size_t t = 0; t < n && seed_a == n; ++t) {
        const size_t u = (start + t) % n;
        for (size_t s = 1; s < n; ++s) {
            const size_t v = (u + s) % n;
            if (!conflicts(u, v)) {
                seed_a = u, seed_b = v;
                break;
            }
        }
    }
    if (seed_a == n) return split;

    // blocked_by[side][x]: how many members of the other side patch x conflicts with.
    std::vector<size_t> blocked_by[2] = {std::vector<size_t>(n, 0), std::vector<size_t>(n, 0)};
    std::vector<bool> placed(n, false);
    std::vector<size_t>* members[2] = {&split.a, &split.b};
    auto place = [&](int side, size_t x) {
        placed[x] = true;
        members[side]->push_back(x);
        for (size_t y = 0; y < n; ++y)
            if (conflicts(x, y)) ++blocked_by[1 - side][y];  // y can no longer join the other side
    };
    place(0, seed_a);
    place(1, seed_b);

    std::vector<size_t> fits;
    bool progress = true;
    while (progress) {
        progress = false;
        for (int side = 0; side < 2; ++side) {
            fits.clear();
            for (size_t x = 0; x < n; ++x)
                if (!placed[x] && blocked_by[side][x] == 0) fits.push_back(x);
            if (fits.empty()) continue;
            place(side, fits[size_t(rng.below(fits.size()))]);
            progress = true;
        }
    }
    std::sort(split.a.begin(), split.a.end());
    std::sort(split.b.begin(), split.b.end());
    return split;
}

}  // namespace tilejet::synth::detail
