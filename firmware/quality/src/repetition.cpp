#include "tilejet/quality/repetition.hpp"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <thread>
#include <unordered_set>

#include "tilejet/synth/error.hpp"
#include "tilejet/synth/internal/mix64.hpp"
#include "tilejet/synth/internal/parallel_for.hpp"

namespace tilejet::quality {

namespace {

using synth::detail::uint128;

constexpr uint64_t kPrime = (uint64_t(1) << 61) - 1;
// Key of a window that cannot be repeated (see measure_repetition); no hash takes this value.
constexpr uint64_t kExcluded = ~uint64_t(0);
// The two bases of the 2D polynomial hash (rows, columns): drawn at random once.
constexpr uint64_t kRowBase = 0x0e2f5a3c91b7d461ull % kPrime;
constexpr uint64_t kColumnBase = 0x13c6ef372fe94f82ull % kPrime;

uint64_t mul_mod(uint64_t a, uint64_t b) {
    const uint128 m = uint128(a) * b;
    const uint64_t r = uint64_t(m & kPrime) + uint64_t(m >> 61);
    return r >= kPrime ? r - kPrime : r;
}
uint64_t add_mod(uint64_t a, uint64_t b) {
    const uint64_t r = a + b;
    return r >= kPrime ? r - kPrime : r;
}
uint64_t sub_mod(uint64_t a, uint64_t b) {
    return a >= b ? a - b : a + kPrime - b;
}
uint64_t pow_mod(uint64_t base, int e) {
    uint64_t r = 1;
    for (int k = 0; k < e; ++k)
        r = mul_mod(r, base);
    return r;
}

// The windows of one size on every tile, numbered tile by tile, row by row.
struct WindowGrid {
    cv::Size window, tile;
    int nx = 0, ny = 0;
    size_t per_tile = 0, tiles = 0;
    WindowGrid(cv::Size w, cv::Size t, size_t n)
        : window(w),
          tile(t),
          nx(t.width - w.width + 1),
          ny(t.height - w.height + 1),
          per_tile(size_t(nx) * size_t(ny)),
          tiles(n) {}
    size_t total() const { return per_tile * tiles; }
};

// Hash of every window of `tile` into keys[0, per_tile): a rolling row hash over window.width
// pixels, then a rolling column hash of those over window.height rows.
void hash_windows(const cv::Mat& tile, const WindowGrid& g, uint64_t* keys) {
    const int sw = g.window.width, sh = g.window.height, h = tile.rows;
    const uint64_t row_out = pow_mod(kRowBase, sw - 1), col_out = pow_mod(kColumnBase, sh - 1);
    std::vector<uint64_t> rows(size_t(h) * size_t(g.nx));
    for (int y = 0; y < h; ++y) {
        const uint8_t* p = tile.ptr<uint8_t>(y);
        // +1 so that black pixels still weigh in the polynomial.
        auto value = [p](int x) {
            return (uint64_t(p[3 * x]) << 16 | uint64_t(p[3 * x + 1]) << 8 | p[3 * x + 2]) + 1;
        };
        uint64_t r = 0;
        for (int x = 0; x < sw; ++x)
            r = add_mod(mul_mod(r, kRowBase), value(x));
        uint64_t* out = rows.data() + size_t(y) * size_t(g.nx);
        out[0] = r;
        for (int x = 1; x < g.nx; ++x) {
            r = add_mod(mul_mod(sub_mod(r, mul_mod(value(x - 1), row_out)), kRowBase),
                        value(x + sw - 1));
            out[x] = r;
        }
    }
    std::vector<uint64_t> acc(size_t(g.nx), 0);
    for (int y = 0; y < sh; ++y)
        for (int x = 0; x < g.nx; ++x)
            acc[size_t(x)] = add_mod(mul_mod(acc[size_t(x)], kColumnBase),
                                     rows[size_t(y) * size_t(g.nx) + size_t(x)]);
    std::copy(acc.begin(), acc.end(), keys);
    for (int y = 1; y < g.ny; ++y) {
        const uint64_t* leaving = rows.data() + size_t(y - 1) * size_t(g.nx);
        const uint64_t* entering = rows.data() + size_t(y + sh - 1) * size_t(g.nx);
        uint64_t* out = keys + size_t(y) * size_t(g.nx);
        for (int x = 0; x < g.nx; ++x) {
            uint64_t& a = acc[size_t(x)];
            a = add_mod(mul_mod(sub_mod(a, mul_mod(leaving[x], col_out)), kColumnBase),
                        entering[x]);
            out[x] = a;
        }
    }
}

struct Matches {
    std::vector<uint64_t> repeated;  // bit per window: its hash occurs at another window too
    std::vector<uint8_t> pairs;      // tiles x tiles, [a * tiles + b] for a < b: share a window
    bool is_repeated(size_t i) const { return (repeated[i / 64] >> (i % 64)) & 1; }
};

struct Entry {
    uint64_t key;
    uint32_t window;
    bool operator<(const Entry& o) const {
        return key < o.key || (key == o.key && window < o.window);
    }
};

// Within one bucket: which entries' keys occur more than once. Counting in a small open-
// addressing table that stays in cache is several times faster than sorting the bucket.
void mark_repeated(const Entry* begin, const Entry* end, std::vector<uint64_t>& table,
                   std::vector<uint8_t>& counts, std::vector<uint64_t>& repeated) {
    size_t slots = 64;
    while (slots < 2 * size_t(end - begin))
        slots *= 2;
    table.assign(slots, 0);
    counts.assign(slots, 0);
    const size_t mask = slots - 1;
    constexpr uint64_t kUsed = uint64_t(1) << 63;  // keys are below 2^61
    auto slot_of = [&](uint64_t key) {
        size_t s = size_t(key) & mask;  // the low bits of a hash mod 2^61 - 1 are uniform
        while (table[s] && table[s] != (key | kUsed))
            s = (s + 1) & mask;
        return s;
    };
    for (const Entry* e = begin; e != end; ++e) {
        const size_t s = slot_of(e->key);
        table[s] = e->key | kUsed;
        if (counts[s] < 2) ++counts[s];
    }
    for (const Entry* e = begin; e != end; ++e)
        if (counts[slot_of(e->key)] > 1)
            std::atomic_ref<uint64_t>(repeated[e->window / 64])
                .fetch_or(uint64_t(1) << (e->window % 64), std::memory_order_relaxed);
}

// Within one bucket sorted by key: every pair of tiles that holds the same key.
void mark_pairs(std::vector<Entry>::iterator begin, std::vector<Entry>::iterator end,
                const WindowGrid& g, std::unordered_set<uint64_t>& seen_tile_sets,
                std::vector<uint8_t>& pairs) {
    std::sort(begin, end);
    std::vector<uint32_t> run_tiles;
    for (auto r = begin; r != end;) {
        auto e = r + 1;
        while (e != end && e->key == r->key)
            ++e;
        if (e - r > 1) {
            run_tiles.clear();
            for (auto k = r; k != e; ++k)
                run_tiles.push_back(uint32_t(k->window / g.per_tile));
            // Ascending already (sorted by window within a key).
            run_tiles.erase(std::unique(run_tiles.begin(), run_tiles.end()), run_tiles.end());
            uint64_t h = run_tiles.size();
            for (uint32_t t : run_tiles)
                h = synth::detail::hash_combine(h, t);
            if (run_tiles.size() > 1 && seen_tile_sets.insert(h).second)
                for (size_t a = 0; a < run_tiles.size(); ++a)
                    for (size_t z = a + 1; z < run_tiles.size(); ++z)
                        pairs[run_tiles[a] * g.tiles + run_tiles[z]] = 1;
        }
        r = e;
    }
}

// Finds equal hashes: windows are bucketed by their hash's top bits (a counting sort, tile by
// tile so that tiles run in parallel), then each bucket is resolved on its own.
Matches find_matches(const std::vector<uint64_t>& keys, const WindowGrid& g, bool want_pairs,
                     int threads, std::vector<Entry>& entries) {
    const size_t total = g.total();
    int bits = 0;
    while (bits < 20 && (total >> bits) > 16384)
        ++bits;
    const size_t buckets = size_t(1) << bits;
    auto bucket_of = [bits](uint64_t key) { return bits ? size_t(key >> (61 - bits)) : 0; };

    std::vector<uint32_t> count(g.tiles * buckets, 0);
    synth::detail::parallel_for(g.tiles, threads, [&](size_t t) {
        uint32_t* c = count.data() + t * buckets;
        for (size_t i = t * g.per_tile; i < (t + 1) * g.per_tile; ++i)
            if (keys[i] != kExcluded) ++c[bucket_of(keys[i])];
    });
    std::vector<size_t> start(buckets + 1, 0), offset(g.tiles * buckets);
    size_t at = 0;
    for (size_t b = 0; b < buckets; ++b) {
        start[b] = at;
        for (size_t t = 0; t < g.tiles; ++t)
            offset[t * buckets + b] = at, at += count[t * buckets + b];
    }
    start[buckets] = at;
    if (entries.size() < at) entries.resize(at);  // reused across sizes: no page faults
    synth::detail::parallel_for(g.tiles, threads, [&](size_t t) {
        size_t* o = offset.data() + t * buckets;
        for (size_t i = t * g.per_tile; i < (t + 1) * g.per_tile; ++i)
            if (keys[i] != kExcluded) entries[o[bucket_of(keys[i])]++] = {keys[i], uint32_t(i)};
    });

    Matches m;
    m.repeated.assign((total + 63) / 64, 0);
    const size_t chunks = size_t(std::max(1, threads)) * 4;
    std::vector<std::vector<uint8_t>> chunk_pairs(chunks);
    synth::detail::parallel_for(chunks, threads, [&](size_t c) {
        std::vector<uint64_t> table;
        std::vector<uint8_t> counts;
        std::unordered_set<uint64_t> seen_tile_sets;
        if (want_pairs) chunk_pairs[c].assign(g.tiles * g.tiles, 0);
        for (size_t b = c * buckets / chunks; b < (c + 1) * buckets / chunks; ++b) {
            const auto first = entries.begin() + std::ptrdiff_t(start[b]);
            const auto last = entries.begin() + std::ptrdiff_t(start[b + 1]);
            mark_repeated(&*first, &*first + (last - first), table, counts, m.repeated);
            if (want_pairs) mark_pairs(first, last, g, seen_tile_sets, chunk_pairs[c]);
        }
    });
    if (want_pairs) {
        m.pairs.assign(g.tiles * g.tiles, 0);
        for (const auto& p : chunk_pairs)
            for (size_t i = 0; i < p.size(); ++i)
                m.pairs[i] |= p[i];
    }
    return m;
}

// Pixels of one tile covered by at least one repeated window; raises `heat` to `level` there.
size_t cover(const Matches& m, size_t first, const WindowGrid& g, cv::Mat& heat, uint8_t level) {
    const int sw = g.window.width, sh = g.window.height, w = g.tile.width, h = g.tile.height;
    // Horizontal pass: row y of window starts -> pixels x covered by a repeated window there.
    std::vector<uint8_t> across(size_t(g.ny) * size_t(w), 0);
    for (int y = 0; y < g.ny; ++y) {
        const size_t row = first + size_t(y) * size_t(g.nx);
        uint8_t* a = across.data() + size_t(y) * size_t(w);
        int last = -(1 << 30);  // latest window start at or left of x that is repeated
        for (int x = 0; x < w; ++x) {
            if (x < g.nx && m.is_repeated(row + size_t(x))) last = x;
            a[x] = x - last < sw;
        }
    }
    std::vector<int> last(size_t(w), -(1 << 30));
    size_t covered = 0;
    for (int y = 0; y < h; ++y) {
        uint8_t* hp = heat.ptr<uint8_t>(y);
        const uint8_t* a = y < g.ny ? across.data() + size_t(y) * size_t(w) : nullptr;
        for (int x = 0; x < w; ++x) {
            if (a && a[x]) last[size_t(x)] = y;
            if (y - last[size_t(x)] < sh) {
                ++covered;
                hp[x] = std::max(hp[x], level);
            }
        }
    }
    return covered;
}

}  // namespace

std::vector<int> repeat_window_sizes(cv::Size tile) {
    std::vector<int> sizes;
    for (int s = 16; s <= 256 && s <= std::min(tile.width, tile.height); s *= 2)
        sizes.push_back(s);
    return sizes;
}

Repetition measure_repetition(const Wall& wall, int threads, const MeasureProgress& progress) {
    for (const cv::Mat& t : wall.tiles)
        if (t.type() != CV_8UC3 || t.size() != wall.tile)
            throw synth::SynthError(
                "every tile of a wall must be 8-bit RGB of the wall's tile size");
    if (threads <= 0) threads = int(std::max(1u, std::thread::hardware_concurrency()));
    Repetition rep;
    const std::vector<int> sizes = repeat_window_sizes(wall.tile);
    rep.shared_window = {(wall.tile.width + 1) / 2, (wall.tile.height + 1) / 2};
    rep.heat.assign(wall.tiles.size(), cv::Mat());
    for (cv::Mat& h : rep.heat)
        h = cv::Mat(wall.tile, CV_8U, cv::Scalar(0));

    const bool pairs_in_curve =
        rep.shared_window.width == rep.shared_window.height &&
        std::find(sizes.begin(), sizes.end(), rep.shared_window.width) != sizes.end();
    std::vector<cv::Size> windows;
    for (int s : sizes)
        windows.emplace_back(s, s);
    if (!pairs_in_curve) windows.push_back(rep.shared_window);

    const size_t n = wall.tiles.size();
    std::vector<uint64_t> keys;
    std::vector<Entry> entries;
    Matches previous;  // of the last curve size, half the current one
    for (size_t w = 0; w < windows.size(); ++w) {
        if (progress) progress("repetition", w, windows.size());
        const WindowGrid g(windows[w], wall.tile, n);
        if (g.total() >= (uint64_t(1) << 32))
            throw synth::SynthError("wall too large for the repeat curve (over 2^32 windows)");
        keys.resize(g.total());
        synth::detail::parallel_for(n, threads, [&](size_t t) {
            hash_windows(wall.tiles[t], g, keys.data() + t * g.per_tile);
        });
        // A 2S window that occurs twice consists of four S windows that each occur twice (at
        // the same offset), so only windows whose four quarters were repeated need matching.
        if (w > 0 && w < sizes.size()) {
            const int half = sizes[w - 1];
            const WindowGrid pg(cv::Size(half, half), wall.tile, n);
            synth::detail::parallel_for(n, threads, [&](size_t t) {
                for (int y = 0; y < g.ny; ++y)
                    for (int x = 0; x < g.nx; ++x) {
                        const size_t q = t * pg.per_tile + size_t(y) * size_t(pg.nx) + size_t(x);
                        const size_t right = size_t(half), down = size_t(half) * size_t(pg.nx);
                        if (!previous.is_repeated(q) || !previous.is_repeated(q + right) ||
                            !previous.is_repeated(q + down) ||
                            !previous.is_repeated(q + down + right))
                            keys[t * g.per_tile + size_t(y) * size_t(g.nx) + size_t(x)] = kExcluded;
                    }
            });
        }
        const bool is_pairs_window = windows[w] == rep.shared_window;
        Matches m = find_matches(keys, g, is_pairs_window, threads, entries);
        if (is_pairs_window && n > 1) {
            size_t sharing = 0;
            for (uint8_t p : m.pairs)
                sharing += p;
            rep.tile_pairs_sharing = double(sharing) / (double(n) * double(n - 1) / 2);
        }
        if (w >= sizes.size()) continue;
        std::vector<size_t> covered(n, 0);
        synth::detail::parallel_for(n, threads, [&](size_t t) {
            covered[t] = cover(m, t * g.per_tile, g, rep.heat[t], uint8_t(w + 1));
        });
        size_t sum = 0;
        for (size_t c : covered)
            sum += c;
        const double share = double(sum) / (double(n) * double(wall.tile.area()));
        rep.curve.push_back({sizes[w], share});
        if (share > kRepeatScaleShare) rep.scale = sizes[w];
        previous = std::move(m);
    }
    if (progress) progress("repetition", windows.size(), windows.size());
    return rep;
}

}  // namespace tilejet::quality
