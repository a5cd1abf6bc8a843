#include "layer_steps.hpp"

#include <algorithm>
#include <array>

namespace tilejet::synth::detail {

namespace {

// The conjugate-gradient solve stops once its residual is this share of where it started: a
// hundredth of a level of an 8-bit channel over steps of tens of levels.
constexpr double kTolerance = 1e-4;

// The value layer `l` has at canvas pixel `p` (channel `c`), if it has one.
bool layer_value(const CanvasLayer& l, cv::Point p, int c, double& v) {
    if (!l.area.contains(p)) return false;
    v = l.image->at<cv::Vec3b>(p + l.offset)[c];
    return true;
}

// The change from `p` to `q` (channel `c`) as the layers either side show it, averaged over
// those that have both pixels; false where neither does.
bool layer_change(const std::vector<CanvasLayer>& layers, int lp, int lq, cv::Point p, cv::Point q,
                  int c, double& change) {
    double sum = 0;
    int n = 0;
    for (const int l : {lp, lq}) {
        if (l < 0) continue;
        double a, b;
        if (layer_value(layers[size_t(l)], p, c, a) && layer_value(layers[size_t(l)], q, c, b))
            sum += b - a, ++n;
    }
    if (n == 0) return false;
    change = sum / n;
    return true;
}

}  // namespace

void remove_layer_steps(cv::Mat& rgb, const cv::Mat& layer_of,
                        const std::vector<CanvasLayer>& layers, const cv::Mat& fixed) {
    CV_Assert(rgb.type() == CV_8UC3 && layer_of.type() == CV_32S && fixed.type() == CV_8U &&
              layer_of.size() == rgb.size() && fixed.size() == rgb.size());
    const int rows = rgb.rows, cols = rgb.cols;
    // Unknowns: the free pixels, in scan order; each with its free neighbours' indices.
    cv::Mat index(rgb.size(), CV_32S, cv::Scalar(-1));
    std::vector<cv::Point> at;
    for (int y = 0; y < rows; ++y)
        for (int x = 0; x < cols; ++x)
            if (!fixed.at<uint8_t>(y, x))
                index.at<int>(y, x) = int(at.size()), at.push_back({x, y});
    const size_t n = at.size();
    if (n == 0) return;
    std::vector<std::array<int, 4>> neighbour(n);
    std::vector<double> degree(n, 0.0);
    const std::array<cv::Point, 4> steps = {cv::Point(1, 0), {-1, 0}, {0, 1}, {0, -1}};
    for (size_t i = 0; i < n; ++i)
        for (size_t s = 0; s < 4; ++s) {
            const cv::Point q = at[i] + steps[s];
            const bool inside = q.x >= 0 && q.y >= 0 && q.x < cols && q.y < rows;
            neighbour[i][s] = inside ? index.at<int>(q) : -1;
            degree[i] += inside;
        }
    // Per channel: the correction d minimising, over all pairs of neighbours (p, q) with p free,
    // (d_q - d_p + excess_pq)^2, where excess is how much more the canvas changes from p to q
    // than the layers there do (nothing between pixels of layers of one kind); fixed pixels'
    // d is 0.
    // The normal equations: sum over q of (d_p - d_q) = sum over q of excess_pq.
    std::vector<double> b(n), d(n), r(n), dir(n), a_dir(n);
    const auto apply = [&](const std::vector<double>& v, std::vector<double>& out) {
        for (size_t i = 0; i < n; ++i) {
            double s = degree[i] * v[i];
            for (const int j : neighbour[i])
                if (j >= 0) s -= v[size_t(j)];
            out[i] = s;
        }
    };
    const auto dot = [&](const std::vector<double>& u, const std::vector<double>& v) {
        double s = 0;
        for (size_t i = 0; i < n; ++i)
            s += u[i] * v[i];
        return s;
    };
    std::vector<cv::Mat> corrected(3);
    cv::Mat excess(rgb.size(), CV_64F);
    for (int c = 0; c < 3; ++c) {
        excess.setTo(0);
        for (size_t i = 0; i < n; ++i) {
            const cv::Point p = at[i];
            const int lp = layer_of.at<int>(p);
            double sum = 0;
            for (const cv::Point& s : steps) {
                const cv::Point q = p + s;
                if (q.x < 0 || q.y < 0 || q.x >= cols || q.y >= rows) continue;
                const int lq = layer_of.at<int>(q);
                if (lq == lp) continue;
                if (lp < 0 || lq < 0 || layers[size_t(lp)].kind == layers[size_t(lq)].kind)
                    continue;
                double change;
                if (!layer_change(layers, lp, lq, p, q, c, change)) continue;
                sum += double(rgb.at<cv::Vec3b>(q)[c]) - double(rgb.at<cv::Vec3b>(p)[c]) - change;
            }
            excess.at<double>(p) = sum;
        }
        bool any = false;
        for (size_t i = 0; i < n; ++i)
            b[i] = excess.at<double>(at[i]), any |= b[i] != 0;
        corrected[size_t(c)] = cv::Mat(rgb.size(), CV_64F, cv::Scalar(0));
        if (!any) continue;
        // Conjugate gradients from d = 0, in scan order throughout: the same bytes whatever
        // the machine and thread count.
        std::fill(d.begin(), d.end(), 0.0);
        r = b, dir = b;
        double rr = dot(r, r);
        const double stop = kTolerance * kTolerance * rr;
        for (size_t iteration = 0; iteration < 4 * n && rr > stop; ++iteration) {
            apply(dir, a_dir);
            const double alpha = rr / dot(dir, a_dir);
            for (size_t i = 0; i < n; ++i)
                d[i] += alpha * dir[i], r[i] -= alpha * a_dir[i];
            const double next = dot(r, r);
            const double beta = next / rr;
            rr = next;
            for (size_t i = 0; i < n; ++i)
                dir[i] = r[i] + beta * dir[i];
        }
        for (size_t i = 0; i < n; ++i)
            corrected[size_t(c)].at<double>(at[i]) = d[i];
    }
    for (int y = 0; y < rows; ++y)
        for (int x = 0; x < cols; ++x) {
            cv::Vec3b& px = rgb.at<cv::Vec3b>(y, x);
            for (int c = 0; c < 3; ++c)
                px[c] = cv::saturate_cast<uint8_t>(double(px[c]) +
                                                   corrected[size_t(c)].at<double>(y, x));
        }
}

}  // namespace tilejet::synth::detail
