#include "cell_image_coding.hpp"

#include <algorithm>
#include <cstring>
#include <unordered_map>

#include "map_bytes.hpp"
#include "tilejet/synth/internal/mix64.hpp"
#include "tilejet/synth/internal/parallel_for.hpp"

namespace tilejet::synth::detail {

namespace {

// Blocks are looked up in the source by the key of a square of this many px at a few places of
// the block: a whole 8 px block straddling a cut is nowhere in the source, a 4 px square of it
// mostly is.
constexpr int kKeySide = 4;

struct Displacement {
    int16_t dx = kNoPrediction, dy = kNoPrediction;
    bool operator==(const Displacement&) const = default;
};

uint64_t key_at(const cv::Mat& rgb, int x, int y) {
    uint64_t h = 0;
    for (int r = 0; r < kKeySide; ++r) {
        const uint8_t* p = rgb.ptr<uint8_t>(y + r) + 3 * x;
        uint64_t a = 0;
        uint32_t b = 0;
        std::memcpy(&a, p, 8);
        std::memcpy(&b, p + 8, 4);
        h = hash_combine(h, a ^ (uint64_t(b) << 1));
    }
    return h;
}

// Where in a block of `size` px its key squares lie: top-left, centre and bottom-right (fewer
// in blocks too small for them).
std::vector<cv::Point> key_places(cv::Size size) {
    std::vector<cv::Point> out;
    if (size.width < kKeySide || size.height < kKeySide) return out;
    const int mx = size.width - kKeySide, my = size.height - kKeySide;
    for (const cv::Point p : {cv::Point(0, 0), cv::Point(mx / 2, my / 2), cv::Point(mx, my)})
        if (std::ranges::find(out, p) == out.end()) out.push_back(p);
    return out;
}

// Coding blocks along `side` px, the last one partial.
int blocks_along(int side) {
    return (side + kCodingBlock - 1) / kCodingBlock;
}

cv::Rect block_rect(int bx, int by, cv::Size cell) {
    const int x = bx * kCodingBlock, y = by * kCodingBlock;
    return {x, y, std::min(kCodingBlock, cell.width - x), std::min(kCodingBlock, cell.height - y)};
}

// How many residual bytes of `block` would not be zero, predicted from the source displaced by
// `d`; SIZE_MAX when that window leaves the source.
size_t nonzero_residuals(const cv::Mat& cell, const cv::Rect& block, const cv::Mat& source,
                         Displacement d) {
    size_t n = 0;
    if (d.dx == kNoPrediction) {
        for (int y = block.y; y < block.br().y; ++y) {
            const uint8_t* p = cell.ptr<uint8_t>(y) + 3 * block.x;
            for (int i = 0; i < 3 * block.width; ++i)
                n += p[i] != 0;
        }
        return n;
    }
    const cv::Rect from = block + cv::Point(d.dx, d.dy);
    if ((from & cv::Rect({0, 0}, source.size())) != from) return SIZE_MAX;
    for (int y = 0; y < block.height; ++y) {
        const uint8_t* p = cell.ptr<uint8_t>(block.y + y) + 3 * block.x;
        const uint8_t* q = source.ptr<uint8_t>(from.y + y) + 3 * from.x;
        for (int i = 0; i < 3 * block.width; ++i)
            n += p[i] != q[i];
    }
    return n;
}

}  // namespace

std::vector<std::vector<uint8_t>> code_cell_images(std::span<const cv::Mat> cells,
                                                   const cv::Mat& source) {
    if (cells.empty()) return {};
    CV_Assert(source.type() == CV_8UC3);
    const cv::Size cell = cells.front().size();
    const int bw = blocks_along(cell.width), bh = blocks_along(cell.height);
    const size_t blocks = size_t(bw) * size_t(bh);

    // What each block's key squares are, and where in the source each was first seen.
    struct Want {
        size_t image, block;
        cv::Point at;  // the key square's top-left in the cell
    };
    std::vector<Want> wants;
    std::unordered_map<uint64_t, std::vector<uint32_t>> wanted;
    for (size_t t = 0; t < cells.size(); ++t) {
        CV_Assert(cells[t].type() == CV_8UC3 && cells[t].size() == cell);
        for (int by = 0; by < bh; ++by)
            for (int bx = 0; bx < bw; ++bx) {
                const cv::Rect r = block_rect(bx, by, cell);
                for (const cv::Point p : key_places(r.size())) {
                    const cv::Point at = r.tl() + p;
                    wanted[key_at(cells[t], at.x, at.y)].push_back(uint32_t(wants.size()));
                    wants.push_back({t, size_t(by) * size_t(bw) + size_t(bx), at});
                }
            }
    }
    // The first place of the source, row by row, whose key each wanted square has (a key
    // shared by two windows merely offers a candidate the block's own test below turns down).
    constexpr uint64_t kUnseen = UINT64_MAX;
    std::vector<uint64_t> seen(wants.size(), kUnseen);
    if (source.cols >= kKeySide && source.rows >= kKeySide)
        for (int y = 0; y + kKeySide <= source.rows; ++y)
            for (int x = 0; x + kKeySide <= source.cols; ++x) {
                const auto it = wanted.find(key_at(source, x, y));
                if (it == wanted.end()) continue;
                for (const uint32_t w : it->second)
                    if (seen[w] == kUnseen) seen[w] = uint64_t(y) * uint64_t(source.cols) + x;
            }
    // Each block's candidates from its key squares.
    std::vector<std::vector<Displacement>> found(cells.size() * blocks);
    for (size_t w = 0; w < wants.size(); ++w) {
        if (seen[w] == kUnseen) continue;
        const int sx = int(seen[w] % uint64_t(source.cols)),
                  sy = int(seen[w] / uint64_t(source.cols));
        const Displacement d{int16_t(sx - wants[w].at.x), int16_t(sy - wants[w].at.y)};
        auto& list = found[wants[w].image * blocks + wants[w].block];
        if (std::ranges::find(list, d) == list.end()) list.push_back(d);
    }

    std::vector<std::vector<uint8_t>> out(cells.size());
    parallel_for(cells.size(), 0, [&](size_t t) {
        const cv::Mat& image = cells[t];
        std::vector<Displacement> chosen(blocks);
        for (int by = 0; by < bh; ++by)
            for (int bx = 0; bx < bw; ++bx) {
                const size_t b = size_t(by) * size_t(bw) + size_t(bx);
                const cv::Rect r = block_rect(bx, by, cell);
                // The neighbours' first: where they copy on, their displacement repeats and
                // zlib stores it for nothing.
                std::vector<Displacement> candidates;
                if (bx > 0) candidates.push_back(chosen[b - 1]);
                if (by > 0) candidates.push_back(chosen[b - size_t(bw)]);
                if (by > 0 && bx + 1 < bw) candidates.push_back(chosen[b - size_t(bw) + 1]);
                for (const Displacement d : found[t * blocks + b])
                    candidates.push_back(d);
                Displacement best{};
                size_t best_cost = nonzero_residuals(image, r, source, best);
                for (const Displacement d : candidates) {
                    if (d.dx == kNoPrediction) continue;
                    const size_t cost = nonzero_residuals(image, r, source, d);
                    if (cost < best_cost) best = d, best_cost = cost;
                }
                chosen[b] = best;
            }
        Writer w;
        w.bytes.reserve(8 + 4 * blocks + size_t(cell.area()) * 3);
        w.le<uint32_t>(uint32_t(cell.width)), w.le<uint32_t>(uint32_t(cell.height));
        for (const Displacement d : chosen)
            w.le<int16_t>(d.dx), w.le<int16_t>(d.dy);
        const size_t residuals = w.bytes.size();
        w.bytes.resize(residuals + size_t(cell.area()) * 3);
        for (int by = 0; by < bh; ++by)
            for (int bx = 0; bx < bw; ++bx) {
                const Displacement d = chosen[size_t(by) * size_t(bw) + size_t(bx)];
                const cv::Rect r = block_rect(bx, by, cell);
                for (int y = r.y; y < r.br().y; ++y) {
                    const uint8_t* p = image.ptr<uint8_t>(y) + 3 * r.x;
                    uint8_t* o = w.bytes.data() + residuals +
                                 (size_t(y) * size_t(cell.width) + size_t(r.x)) * 3;
                    const uint8_t* q = d.dx == kNoPrediction
                                           ? nullptr
                                           : source.ptr<uint8_t>(y + d.dy) + 3 * (r.x + d.dx);
                    for (int i = 0; i < 3 * r.width; ++i)
                        o[i] = uint8_t(p[i] - (q ? q[i] : 0));
                }
            }
        out[t] = std::move(w.bytes);
    });
    return out;
}

cv::Mat decode_cell_image(std::span<const uint8_t> coded, const cv::Mat& source, cv::Size cell,
                          const std::string& where) {
    Reader r(coded, where);
    const auto w = r.le<uint32_t>("image width"), h = r.le<uint32_t>("image height");
    if (w != uint32_t(cell.width) || h != uint32_t(cell.height))
        r.fail("cell image size " + std::to_string(w) + "x" + std::to_string(h) +
               " differs from the cell size");
    const int bw = blocks_along(cell.width), bh = blocks_along(cell.height);
    const size_t blocks = size_t(bw) * size_t(bh), pixels = size_t(cell.area()) * 3;
    if (r.remaining() != 4 * blocks + pixels)
        r.fail("holds " + std::to_string(r.remaining()) +
               " bytes of displacements and residuals, " + std::to_string(4 * blocks + pixels) +
               " expected");
    std::vector<Displacement> displacements(blocks);
    for (Displacement& d : displacements)
        d.dx = r.le<int16_t>("displacement"), d.dy = r.le<int16_t>("displacement");
    const uint8_t* residual = r.take(pixels, "residuals").data();
    cv::Mat out(cell, CV_8UC3);
    for (int by = 0; by < bh; ++by)
        for (int bx = 0; bx < bw; ++bx) {
            const Displacement d = displacements[size_t(by) * size_t(bw) + size_t(bx)];
            const cv::Rect block = block_rect(bx, by, cell);
            const bool predicted = d != Displacement{};
            if (predicted) {
                const cv::Rect from = block + cv::Point(d.dx, d.dy);
                if ((from & cv::Rect({0, 0}, source.size())) != from)
                    r.fail("block " + std::to_string(bx) + "," + std::to_string(by) +
                           " copies from outside the source (displacement " + std::to_string(d.dx) +
                           "," + std::to_string(d.dy) + ")");
            }
            for (int y = block.y; y < block.br().y; ++y) {
                uint8_t* o = out.ptr<uint8_t>(y) + 3 * block.x;
                const uint8_t* e =
                    residual + (size_t(y) * size_t(cell.width) + size_t(block.x)) * 3;
                const uint8_t* q =
                    predicted ? source.ptr<uint8_t>(y + d.dy) + 3 * (block.x + d.dx) : nullptr;
                for (int i = 0; i < 3 * block.width; ++i)
                    o[i] = uint8_t(e[i] + (q ? q[i] : 0));
            }
        }
    r.done();
    return out;
}

}  // namespace tilejet::synth::detail
