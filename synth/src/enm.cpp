#include "tilejet/synth/internal/enm.hpp"

#include <algorithm>
#include <opencv2/flann.hpp>
#include <unordered_map>
#include <vector>

#include "tilejet/synth/error.hpp"
#include "tilejet/synth/internal/mix64.hpp"

namespace tilejet::synth {

namespace {

using detail::Rng;

// In flat areas one colour can occur at thousands of positions, all about equally good;
// looking at a random few of them keeps every pixel's search short.
constexpr size_t kMaxCandidatesPerNeighbour = 64;

uint32_t colour_key(const cv::Vec3b& c) {
    return uint32_t(c[0]) << 16 | uint32_t(c[1]) << 8 | c[2];
}

// Where each colour occurs in the exemplar. Exact lookups go through a hash table; with a
// tolerance, a kd-tree over the distinct colours (FLANN, searched exhaustively so the answer
// is exact) finds the colours within it, cached per query colour.
class ColourIndex {
  public:
    ColourIndex(const cv::Mat& exemplar, int tolerance) : tolerance_(tolerance) {
        std::unordered_map<uint32_t, size_t> group_of;
        for (int y = 0; y < exemplar.rows; ++y)
            for (int x = 0; x < exemplar.cols; ++x) {
                const uint32_t key = colour_key(exemplar.at<cv::Vec3b>(y, x));
                auto [it, fresh] = group_of.try_emplace(key, groups_.size());
                if (fresh) groups_.emplace_back(), keys_.push_back(key);
                groups_[it->second].push_back(y * exemplar.cols + x);
            }
        if (tolerance_ == 0) {
            for (auto& [key, group] : group_of)
                exact_.emplace(key, std::vector<size_t>{group});
            return;
        }
        colours_ = cv::Mat(int(keys_.size()), 3, CV_32F);
        for (size_t i = 0; i < keys_.size(); ++i) {
            float* row = colours_.ptr<float>(int(i));
            row[0] = float(keys_[i] >> 16), row[1] = float(keys_[i] >> 8 & 255),
            row[2] = float(keys_[i] & 255);
        }
        tree_ = std::make_unique<cv::flann::Index>(colours_, cv::flann::KDTreeIndexParams(1));
    }

    // The groups of exemplar pixel indices whose colour matches `c`.
    const std::vector<size_t>& matching(const cv::Vec3b& c) {
        const uint32_t key = colour_key(c);
        if (auto it = exact_.find(key); it != exact_.end()) return it->second;
        std::vector<size_t>& found = exact_[key];
        if (!tree_) return found;
        const cv::Mat query = (cv::Mat_<float>(1, 3) << c[0], c[1], c[2]);
        std::vector<int> indices;
        std::vector<float> distances;
        // FLANN's L2 radius is squared; unlimited checks make the search exact.
        const int n = tree_->radiusSearch(query, indices, distances, float(tolerance_ * tolerance_),
                                          colours_.rows,
                                          cv::flann::SearchParams(cvflann::FLANN_CHECKS_UNLIMITED));
        for (int i = 0; i < n && i < int(indices.size()); ++i)
            found.push_back(size_t(indices[size_t(i)]));
        std::sort(found.begin(), found.end());
        return found;
    }
    const std::vector<int>& group(size_t g) const { return groups_[g]; }

  private:
    int tolerance_;
    std::vector<std::vector<int>> groups_;
    std::vector<uint32_t> keys_;
    std::unordered_map<uint32_t, std::vector<size_t>> exact_;
    cv::Mat colours_;
    std::unique_ptr<cv::flann::Index> tree_;
};

class Synthesis {
  public:
    Synthesis(const cv::Mat& exemplar, cv::Size size, const EnmParams& params, Rng& rng)
        : ex_(exemplar), r_(params.radius), out_(size, CV_8UC3), rng_(rng) {
        for (int dy = -r_; dy <= 0; ++dy)
            for (int dx = -r_; dx <= r_; ++dx)
                if (dy < 0 || dx < 0) causal_.emplace_back(dx, dy);
        // Centres whose whole causal neighbourhood lies in the exemplar.
        valid_ = cv::Rect(r_, r_, ex_.cols - 2 * r_, ex_.rows - r_);
        stamp_.assign(ex_.total(), 0);
    }

    cv::Mat run(const EnmParams& params) {
        ColourIndex index(ex_,
                          params.search == EnmParams::Search::ExactMatch ? params.tolerance : 0);
        const int seed_side = std::min({2 * r_ + 1, out_.cols, out_.rows});
        // The seed block must lie wholly in the exemplar, not just its centre.
        const cv::Point seed(int(rng_.below(uint64_t(ex_.cols - seed_side + 1))),
                             int(rng_.below(uint64_t(ex_.rows - seed_side + 1))));
        for (int y = 0; y < out_.rows; ++y)
            for (int x = 0; x < out_.cols; ++x) {
                cv::Point from;
                if (x < seed_side && y < seed_side)
                    from = seed + cv::Point(x, y);
                else if (params.search == EnmParams::Search::BruteForce)
                    from = brute_force({x, y});
                else
                    from = exact_match({x, y}, index);
                out_.at<cv::Vec3b>(y, x) = ex_.at<cv::Vec3b>(from);
            }
        return out_;
    }

  private:
    cv::Point random_valid() {
        return {valid_.x + int(rng_.below(uint64_t(valid_.width))),
                valid_.y + int(rng_.below(uint64_t(valid_.height)))};
    }

    // Squared R,G,B distance between the output's causal neighbourhood at `at` and the
    // exemplar's at `s`, over the output pixels that exist.
    int distance(cv::Point at, cv::Point s) const {
        int sum = 0;
        for (const cv::Point& d : causal_) {
            const cv::Point o = at + d;
            if (o.x < 0 || o.x >= out_.cols || o.y < 0) continue;
            const cv::Vec3b a = out_.at<cv::Vec3b>(o), b = ex_.at<cv::Vec3b>(s + d);
            for (int k = 0; k < 3; ++k)
                sum += (int(a[k]) - int(b[k])) * (int(a[k]) - int(b[k]));
        }
        return sum;
    }

    // Best so far, with ties broken at random (reservoir sampling) so flat areas do not always
    // copy from the same place.
    struct Best {
        cv::Point at{-1, -1};
        int cost = 0, ties = 0;
    };
    void consider(Best& best, cv::Point at, cv::Point s) {
        const int cost = distance(at, s);
        if (best.at.x < 0 || cost < best.cost)
            best = {s, cost, 1};
        else if (cost == best.cost && rng_.below(uint64_t(++best.ties)) == 0)
            best.at = s;
    }

    cv::Point brute_force(cv::Point at) {
        Best best;
        for (int y = valid_.y; y < valid_.br().y; ++y)
            for (int x = valid_.x; x < valid_.br().x; ++x)
                consider(best, at, {x, y});
        return best.at;
    }

    cv::Point exact_match(cv::Point at, ColourIndex& index) {
        static const cv::Point kDirect[] = {{-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
        Best best;
        ++generation_;
        for (const cv::Point& d : kDirect) {
            const cv::Point n = at + d;
            if (n.x < 0 || n.y < 0 || n.x >= out_.cols) continue;
            const std::vector<size_t>& groups = index.matching(out_.at<cv::Vec3b>(n));
            size_t total = 0;
            for (size_t g : groups)
                total += index.group(g).size();
            auto nth = [&](size_t i) {
                for (size_t g : groups) {
                    if (i < index.group(g).size()) return index.group(g)[i];
                    i -= index.group(g).size();
                }
                return 0;
            };
            const size_t take = std::min(total, kMaxCandidatesPerNeighbour);
            for (size_t k = 0; k < take; ++k) {
                const int p = nth(total <= kMaxCandidatesPerNeighbour ? k : rng_.below(total));
                const cv::Point s = cv::Point(p % ex_.cols, p / ex_.cols) - d;
                if (!valid_.contains(s)) continue;
                uint32_t& seen = stamp_[size_t(s.y) * size_t(ex_.cols) + size_t(s.x)];
                if (seen == generation_) continue;
                seen = generation_;
                consider(best, at, s);
            }
        }
        return best.at.x < 0 ? random_valid() : best.at;
    }

    const cv::Mat& ex_;
    int r_;
    cv::Mat out_;
    Rng& rng_;
    std::vector<cv::Point> causal_;
    cv::Rect valid_;
    std::vector<uint32_t> stamp_;
    uint32_t generation_ = 0;
};

}  // namespace

cv::Mat synthesize_enm(const cv::Mat& exemplar, cv::Size size, uint64_t seed,
                       const EnmParams& params) {
    if (exemplar.type() != CV_8UC3) throw SynthError("enm needs an 8-bit R,G,B exemplar");
    if (params.radius < 1 || params.radius > 8)
        throw SynthError("enm neighbourhood radius " + std::to_string(params.radius) +
                         " must be between 1 and 8");
    if (params.tolerance < 0 || params.tolerance > 441)
        throw SynthError("enm colour tolerance " + std::to_string(params.tolerance) +
                         " must be between 0 and 441");
    if (exemplar.cols < 2 * params.radius + 2 || exemplar.rows < params.radius + 2)
        throw SynthError("exemplar is too small for an enm neighbourhood of radius " +
                         std::to_string(params.radius));
    Rng rng(detail::hash_combine(seed, 0xe7e7ull));
    return Synthesis(exemplar, size, params, rng).run(params);
}

}  // namespace tilejet::synth
