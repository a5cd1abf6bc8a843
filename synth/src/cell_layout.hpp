#pragma once

// Where a cell image's own blocks go (docs/design.md section 9): how deep into the cell it keeps
// its frame strips at each place along its edges, and where the joints between its inside
// blocks lie. Both were the same in every image until session 32, and a wall showed it: every
// cell's cut into its frame ran in the same thin band 2 to 10 px inside its borders, its blocks
// met at the same places, and at half size the cells stood out as squares (the corpus's marble,
// limestone, slate and wood; `tilejet eval`'s lines along the cell grid, 1.24-1.98 where the
// gravel that shows none measures 1.06). Where both wander, image by image, what lines remain
// lie at other places in every cell.

#include <opencv2/core/types.hpp>
#include <utility>
#include <vector>

#include "tilejet/synth/internal/mix64.hpp"

namespace tilejet::synth::detail {

// How deep (px) a cell keeps its strips at each place along each edge: `top[x]` rows from the
// top edge at column x, `left[y]` columns from the left edge at row y, and so on.
struct KeptFrame {
    std::vector<int> top, bottom, left, right;

    // Whether pixel `p` of a `cell` lies within what the cell keeps.
    bool keeps(cv::Point p, cv::Size cell) const {
        return p.y < top[size_t(p.x)] || cell.height - 1 - p.y < bottom[size_t(p.x)] ||
               p.x < left[size_t(p.y)] || cell.width - 1 - p.x < right[size_t(p.y)];
    }
};

// The least and most a cell keeps, and the least within `corner_reach` px of a corner (where
// the corner cores' quarters lie).
struct KeptDepths {
    int least = 2, most = 2, corner_least = 2, corner_reach = 0;
};

// A depth that wanders between `least` and `most` along each edge: smooth steps between random
// depths every sixth of the edge or so, drawn from `rng` (integers only, the same bytes on
// every machine). With `least` == `most`, the straight frame of sets before session 32.
KeptFrame kept_frame(cv::Size cell, const KeptDepths& depths, Rng& rng);

// Starts and ends of blocks that cover [begin, end) with at least `overlap` between neighbours,
// each about `block` long.
std::vector<std::pair<int, int>> block_spans(int begin, int end, int block, int overlap);

// `spans` with each joint between neighbours moved by up to `reach` px either way, drawn from
// `rng`: the overlap of each pair of neighbours stays as it was, the outer ends stay put.
std::vector<std::pair<int, int>> jittered_spans(std::vector<std::pair<int, int>> spans, int reach,
                                                Rng& rng);

}  // namespace tilejet::synth::detail
