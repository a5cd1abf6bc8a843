#include <algorithm>
#include <cmath>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <tuple>
#include <vector>

#include "analysis_size.hpp"
#include "tilejet/synth/lattice.hpp"

namespace tilejet::synth {

namespace {

constexpr double kAlpha = 1.12;         // score = mean^alpha * n^(alpha - 1)
constexpr double kTileCoverage = 0.85;  // a value counts if its overlap covers 85% of a tile
constexpr double kMinPeak = 0.1;        // correlation peaks weaker than this are noise
constexpr double kNearRegular = 0.3;    // mean correlation at lattice points: a lattice at all
constexpr double kRegular = 0.75;       // ... and a strict one
constexpr int kMinPeriod = 4;           // px; shorter repeats are grain, not a lattice
constexpr size_t kMaxPeaks = 24;
constexpr double kBlurSigma = 1.0;  // px
// Courses: the self-correlation across them, at whole multiples of the pitch, must stand at
// least kCourseContrast above itself half a pitch earlier, on average, and be at least
// kCourseCorrelation at one pitch. The corpus's brick wall (joints anywhere along the courses)
// stands 0.235 above and correlates 0.28; marble, wood and granite fall steadily (below 0).
// Its setts stand 0.17 above along their rows and 0.25 along their wandering columns (0.14 at
// one pitch): maps held to either merged stones and repeated (periodicity 1.23), so they stay
// stochastic.
constexpr double kCourseContrast = 0.2;
constexpr double kCourseCorrelation = 0.2;
constexpr double kPitchStep = 0.05;  // px: pitches tried
constexpr int kMinTeeth = 3;         // whole pitches within reach: fewer is not a course
constexpr double kShortestShare = 0.8;

// The generalized normalized cross-correlation of the image with itself, for every displacement
// whose overlap spans at least a third of the image each way. Also the appearance term: mean
// squared difference over the overlap relative to twice the variance.
class SelfCorrelation {
  public:
    explicit SelfCorrelation(const cv::Mat& rgb) : w_(rgb.cols), h_(rgb.rows) {
        max_dx_ = w_ - std::max(1, w_ / 3);
        max_dy_ = h_ - std::max(1, h_ / 3);
        ncc_ = cv::Mat(2 * max_dy_ + 1, 2 * max_dx_ + 1, CV_64F, cv::Scalar(0));
        msd_ = cv::Mat(ncc_.size(), CV_64F, cv::Scalar(0));

        std::vector<cv::Mat> channels;
        cv::Mat unit;
        rgb.convertTo(unit, CV_64FC3, 1.0 / 255);
        // A light blur: real lattices fall between pixels, and sharp edges would make every
        // half-pixel misalignment look like a poor repeat; it also quietens sensor noise.
        cv::GaussianBlur(unit, unit, cv::Size(0, 0), kBlurSigma);
        cv::split(unit, channels);
        double energy[3], total = 0;
        for (int c = 0; c < 3; ++c) {
            cv::Scalar mean, sd;
            cv::meanStdDev(channels[size_t(c)], mean, sd);
            energy[c] = sd[0] * sd[0];
            total += energy[c];
        }
        flat_ = total < 1e-10;
        if (flat_) return;
        for (int c = 0; c < 3; ++c)
            if (energy[c] > 1e-12 * total) add_channel(channels[size_t(c)], energy[c] / total);
    }

    bool flat() const { return flat_; }
    int max_dx() const { return max_dx_; }
    int max_dy() const { return max_dy_; }
    bool in_range(cv::Point d) const {
        return std::abs(d.x) <= max_dx_ && std::abs(d.y) <= max_dy_;
    }
    double ncc(cv::Point d) const { return ncc_.at<double>(d.y + max_dy_, d.x + max_dx_); }
    double msd(cv::Point d) const { return msd_.at<double>(d.y + max_dy_, d.x + max_dx_); }
    double overlap(cv::Point d) const { return double(w_ - std::abs(d.x)) * (h_ - std::abs(d.y)); }

  private:
    void add_channel(const cv::Mat& plane, double weight) {
        // Cross term for all displacements at once: autocorrelation by FFT, zero-padded so it
        // does not wrap.
        const cv::Size size(cv::getOptimalDFTSize(2 * w_), cv::getOptimalDFTSize(2 * h_));
        cv::Mat padded(size, CV_64F, cv::Scalar(0)), spectrum, power, auto_corr;
        plane.copyTo(padded(cv::Rect(0, 0, w_, h_)));
        cv::dft(padded, spectrum);
        cv::mulSpectrums(spectrum, spectrum, power, 0, true);
        cv::dft(power, auto_corr, cv::DFT_INVERSE | cv::DFT_SCALE | cv::DFT_REAL_OUTPUT);
        cv::Mat sum, sqsum;
        cv::integral(plane, sum, sqsum, CV_64F, CV_64F);
        auto rect = [](const cv::Mat& s, int x, int y, int w, int h) {
            return s.at<double>(y + h, x + w) - s.at<double>(y, x + w) - s.at<double>(y + h, x) +
                   s.at<double>(y, x);
        };
        for (int dy = -max_dy_; dy <= max_dy_; ++dy)
            for (int dx = -max_dx_; dx <= max_dx_; ++dx) {
                const int ow = w_ - std::abs(dx), oh = h_ - std::abs(dy);
                const int ax = std::max(0, -dx), ay = std::max(0, -dy);  // p runs over A
                const int bx = std::max(0, dx), by = std::max(0, dy);    // p + d over B
                const double n = double(ow) * oh;
                const double sa = rect(sum, ax, ay, ow, oh), sb = rect(sum, bx, by, ow, oh);
                const double qa = rect(sqsum, ax, ay, ow, oh), qb = rect(sqsum, bx, by, ow, oh);
                const double cross = auto_corr.at<double>((dy + size.height) % size.height,
                                                          (dx + size.width) % size.width);
                const double cov = cross - sa * sb / n;
                const double va = qa - sa * sa / n, vb = qb - sb * sb / n;
                const double ncc = va > 1e-12 && vb > 1e-12 ? cov / std::sqrt(va * vb) : 0;
                const double msd = (qa + qb - 2 * cross) / n / std::max(1e-12, (va + vb) / n);
                ncc_.at<double>(dy + max_dy_, dx + max_dx_) += weight * ncc;
                msd_.at<double>(dy + max_dy_, dx + max_dx_) += weight * msd;
            }
    }

    int w_, h_, max_dx_ = 0, max_dy_ = 0;
    bool flat_ = false;
    cv::Mat ncc_, msd_;
};

bool upper_half(cv::Point d) {
    return d.y > 0 || (d.y == 0 && d.x > 0);
}
double length2(cv::Point p) {
    return double(p.x) * p.x + double(p.y) * p.y;
}

std::vector<cv::Point> correlation_peaks(const SelfCorrelation& sc) {
    std::vector<std::pair<double, cv::Point>> peaks;
    for (int dy = 0; dy <= sc.max_dy(); ++dy)
        for (int dx = -sc.max_dx(); dx <= sc.max_dx(); ++dx) {
            const cv::Point d(dx, dy);
            if (!upper_half(d) || length2(d) < kMinPeriod * kMinPeriod) continue;
            const double v = sc.ncc(d);
            if (v < kMinPeak) continue;
            bool is_max = true;
            for (int ny = -1; ny <= 1 && is_max; ++ny)
                for (int nx = -1; nx <= 1 && is_max; ++nx) {
                    const cv::Point n(dx + nx, dy + ny);
                    if ((nx || ny) && sc.in_range(n) && sc.ncc(n) > v) is_max = false;
                }
            if (is_max) peaks.emplace_back(v, d);
        }
    // The strongest peaks are often far multiples that happen to fall on whole pixels; the
    // fundamental vectors are the short ones among the strong. Keep the peaks at least half as
    // strong as the strongest, shortest first; the pair score then chooses.
    double strongest = 0;
    for (const auto& p : peaks)
        strongest = std::max(strongest, p.first);
    std::erase_if(peaks, [&](const auto& p) { return p.first < 0.5 * strongest; });
    std::sort(peaks.begin(), peaks.end(), [](const auto& a, const auto& b) {
        const double la = length2(a.second), lb = length2(b.second);
        return la != lb ? la < lb
                        : std::tie(a.second.y, a.second.x) < std::tie(b.second.y, b.second.x);
    });
    std::vector<cv::Point> out;
    for (size_t i = 0; i < peaks.size() && i < kMaxPeaks; ++i)
        out.push_back(peaks[i].second);
    return out;
}

// Lagrange-Gauss reduction: the shortest basis of the lattice the pair generates, so that
// (v1, v2), (v2, v1), (v1, v1 + v2) ... all become one candidate.
std::pair<cv::Point, cv::Point> reduce(cv::Point a, cv::Point b) {
    for (int guard = 0; guard < 64; ++guard) {
        if (length2(b) < length2(a)) std::swap(a, b);
        const double m = std::round((double(a.x) * b.x + double(a.y) * b.y) / length2(a));
        if (m == 0) break;
        b -= cv::Point(int(m) * a.x, int(m) * a.y);
    }
    if (!upper_half(a)) a = -a;
    if (!upper_half(b)) b = -b;
    return {a, b};
}

struct PairScore {
    double score = 0, mean_ncc = 0, mean_msd = 0;
    int n = 0;
};

PairScore score_pair(const SelfCorrelation& sc, cv::Point v1, cv::Point v2, double tile_area) {
    PairScore s;
    const int reach =
        int(std::max(sc.max_dx(), sc.max_dy()) / std::sqrt(std::min(length2(v1), length2(v2)))) + 1;
    const int r = std::min(reach, 64);
    for (int i = -r; i <= r; ++i)
        for (int j = -r; j <= r; ++j) {
            const cv::Point d(i * v1.x + j * v2.x, i * v1.y + j * v2.y);
            if (!upper_half(d) || !sc.in_range(d)) continue;
            if (sc.overlap(d) < kTileCoverage * tile_area) continue;
            // Real lattices are rarely whole pixels (a hexagonal mosaic's rows are 0.866 of a
            // period apart): each multiple counts at its best pixel within +-1.
            double best_ncc = -1, best_msd = 0;
            for (int ny = -1; ny <= 1; ++ny)
                for (int nx = -1; nx <= 1; ++nx) {
                    const cv::Point q = d + cv::Point(nx, ny);
                    if (sc.in_range(q) && sc.ncc(q) > best_ncc)
                        best_ncc = sc.ncc(q), best_msd = sc.msd(q);
                }
            s.mean_ncc += best_ncc;
            s.mean_msd += best_msd;
            ++s.n;
        }
    if (s.n < 2) return {};
    s.mean_ncc /= s.n;
    s.mean_msd /= s.n;
    if (s.mean_ncc <= 0) return {};
    s.score = std::pow(s.mean_ncc, kAlpha) * std::pow(double(s.n), kAlpha - 1);
    return s;
}

// The self-correlation at a fractional displacement t across the courses (linear between the
// two pixels).
double across(const SelfCorrelation& sc, bool vertical_pitch, double t) {
    const int i = int(std::floor(t));
    const double f = t - i;
    auto at = [&](int k) { return sc.ncc(vertical_pitch ? cv::Point(0, k) : cv::Point(k, 0)); };
    return (1 - f) * at(i) + f * at(i + 1);
}

struct CourseScore {
    double pitch = 0, contrast = -1;
};

// The pitch whose multiples stand highest above the half pitches between them (a comb: a
// fraction of the pitch puts teeth in the troughs). Odd multiples of the pitch stand as high
// with fewer teeth; the shortest pitch nearly as good as the best is the courses' own.
CourseScore course_pitch(const SelfCorrelation& sc, bool vertical_pitch) {
    const int reach = vertical_pitch ? sc.max_dy() : sc.max_dx();
    std::vector<CourseScore> scores;
    for (double p = kMinPeriod; kMinTeeth * p <= reach - 1; p += kPitchStep) {
        double sum = 0;
        int teeth = 0;
        for (double t = p; t <= reach - 1; t += p, ++teeth)
            sum += across(sc, vertical_pitch, t) - across(sc, vertical_pitch, t - p / 2);
        scores.push_back({p, sum / teeth});
    }
    double best = -1;
    for (const CourseScore& c : scores)
        best = std::max(best, c.contrast);
    for (size_t i = 0; i < scores.size(); ++i) {
        const bool peak = (i == 0 || scores[i - 1].contrast <= scores[i].contrast) &&
                          (i + 1 == scores.size() || scores[i + 1].contrast <= scores[i].contrast);
        if (peak && scores[i].contrast >= kShortestShare * best) return scores[i];
    }
    return {};
}

// Courses in either direction, when they stand out; the stronger of the two when both do.
std::optional<Lattice> detect_courses(const SelfCorrelation& sc) {
    std::optional<Lattice> found;
    for (const bool vertical_pitch : {true, false}) {
        const CourseScore c = course_pitch(sc, vertical_pitch);
        if (c.contrast < kCourseContrast ||
            across(sc, vertical_pitch, c.pitch) < kCourseCorrelation)
            continue;
        if (found && c.contrast <= found->score) continue;
        Lattice l;
        l.kind = LatticeKind::Courses;
        l.pitch = c.pitch;
        l.score = c.contrast;
        const int whole = int(std::lround(c.pitch));
        l.v1 = vertical_pitch ? cv::Point(1, 0) : cv::Point(0, 1);
        l.v2 = vertical_pitch ? cv::Point(0, whole) : cv::Point(whole, 0);
        l.geometry_regularity = across(sc, vertical_pitch, c.pitch);
        l.appearance_regularity =
            std::clamp(1.0 - (vertical_pitch ? sc.msd({0, whole}) : sc.msd({whole, 0})), 0.0, 1.0);
        found = l;
    }
    return found;
}

Lattice detect_as_is(const cv::Mat& rgb) {
    Lattice stochastic;
    const SelfCorrelation sc(rgb);
    if (sc.flat()) return stochastic;
    const std::vector<cv::Point> peaks = correlation_peaks(sc);

    std::map<std::tuple<int, int, int, int>, bool> seen;
    PairScore best;
    cv::Point best_v1, best_v2;
    for (size_t a = 0; a < peaks.size(); ++a)
        for (size_t b = a + 1; b < peaks.size(); ++b) {
            const int det = peaks[a].x * peaks[b].y - peaks[a].y * peaks[b].x;
            if (std::abs(det) < kMinPeriod * kMinPeriod) continue;
            auto [v1, v2] = reduce(peaks[a], peaks[b]);
            if (!seen.emplace(std::tuple{v1.x, v1.y, v2.x, v2.y}, true).second) continue;
            if (length2(v1) < kMinPeriod * kMinPeriod) continue;
            const PairScore s = score_pair(sc, v1, v2, std::abs(double(det)));
            if (s.score > best.score) best = s, best_v1 = v1, best_v2 = v2;
        }
    // Courses win over no lattice, over a lattice so coarse that the courses fit twice into
    // its shortest vector (the pair score found far multiples of irregular stones), and over
    // one whose shortest vector is under half a pitch (smooth bricks correlate with themselves
    // a few pixels along the course).
    const std::optional<Lattice> courses = detect_courses(sc);
    const bool two_way = best.score > 0 && best.mean_ncc >= kNearRegular;
    const double shortest = std::sqrt(std::min(length2(best_v1), length2(best_v2)));
    if (courses && (!two_way || shortest > 2 * courses->pitch || shortest < courses->pitch / 2))
        return *courses;
    if (!two_way) return stochastic;

    Lattice l;
    l.v1 = best_v1, l.v2 = best_v2;
    l.score = best.score;
    l.kind = best.mean_ncc >= kRegular ? LatticeKind::Regular : LatticeKind::NearRegular;
    l.geometry_regularity = best.mean_ncc;
    l.appearance_regularity = std::clamp(1.0 - best.mean_msd, 0.0, 1.0);
    return l;
}

// The normalized correlation of `grey` with itself shifted by `shift`, over their overlap,
// sampled on a grid of about a million points.
double shifted_ncc(const cv::Mat& grey, cv::Point shift) {
    const int x0 = std::max(0, -shift.x), x1 = std::min(grey.cols, grey.cols - shift.x);
    const int y0 = std::max(0, -shift.y), y1 = std::min(grey.rows, grey.rows - shift.y);
    if (x1 - x0 < 2 || y1 - y0 < 2) return -1;
    const int stride = std::max(1, int(std::sqrt(double(x1 - x0) * double(y1 - y0) / 1e6)));
    double n = 0, sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
    for (int y = y0; y < y1; y += stride) {
        const auto* a = grey.ptr<std::uint8_t>(y);
        const auto* b = grey.ptr<std::uint8_t>(y + shift.y) + shift.x;
        for (int x = x0; x < x1; x += stride) {
            const double u = a[x], v = b[x];
            n += 1, sa += u, sb += v, saa += u * u, sbb += v * v, sab += u * v;
        }
    }
    const double den = (n * saa - sa * sa) * (n * sbb - sb * sb);
    return den > 0 ? (n * sab - sa * sb) / std::sqrt(den) : -1;
}

// A lattice found `scale` times smaller, brought to full size: its vectors scaled, then moved
// to where the full image correlates best with itself within a pixel of the smaller one's.
Lattice scaled_up(Lattice l, const cv::Mat& rgb, double scale) {
    cv::Mat grey;
    cv::cvtColor(rgb, grey, cv::COLOR_RGB2GRAY);
    const int reach = int(std::ceil(scale));
    if (l.kind == LatticeKind::Courses) {
        const cv::Point across = l.v1.x == 1 ? cv::Point(0, 1) : cv::Point(1, 0);
        const int guess = int(std::lround(l.pitch * scale));
        int best = guess;
        double best_ncc = -2;
        std::map<int, double> ncc;
        for (int t = std::max(1, guess - reach); t <= guess + reach; ++t) {
            ncc[t] = shifted_ncc(grey, across * t);
            if (ncc[t] > best_ncc) best_ncc = ncc[t], best = t;
        }
        // A fraction of a pixel adds up over courses: the peak of a parabola through the best
        // whole pitch and its neighbours.
        double pitch = best;
        if (ncc.count(best - 1) && ncc.count(best + 1)) {
            const double a = ncc[best - 1], b = ncc[best], c = ncc[best + 1];
            const double curve = a - 2 * b + c;
            if (curve < 0) pitch += std::clamp(0.5 * (a - c) / curve, -0.5, 0.5);
        }
        l.pitch = pitch;
        l.v2 = across * int(std::lround(pitch));
        return l;
    }
    for (cv::Point* v : {&l.v1, &l.v2}) {
        const cv::Point guess(int(std::lround(v->x * scale)), int(std::lround(v->y * scale)));
        double best_ncc = -2;
        for (int dy = -reach; dy <= reach; ++dy)
            for (int dx = -reach; dx <= reach; ++dx) {
                const cv::Point candidate = guess + cv::Point(dx, dy);
                const double ncc = shifted_ncc(grey, candidate);
                if (ncc > best_ncc) best_ncc = ncc, *v = candidate;
            }
    }
    return l;
}

}  // namespace

std::string_view lattice_kind_name(LatticeKind kind) {
    switch (kind) {
        case LatticeKind::Regular:
            return "regular";
        case LatticeKind::NearRegular:
            return "near-regular";
        case LatticeKind::Courses:
            return "courses";
        case LatticeKind::Stochastic:
            return "stochastic";
    }
    return "stochastic";
}

Lattice detect_lattice(const cv::Mat& rgb) {
    CV_Assert(rgb.type() == CV_8UC3);
    const double scale = detail::analysis_scale(rgb.size());
    if (scale == 1) return detect_as_is(rgb);
    // A slab scan is looked at smaller (analysis_size.hpp), its lattice then fitted to it.
    const Lattice found = detect_as_is(detail::analysis_copy(rgb));
    if (found.kind == LatticeKind::Stochastic) return found;
    return scaled_up(found, rgb, scale);
}

}  // namespace tilejet::synth
