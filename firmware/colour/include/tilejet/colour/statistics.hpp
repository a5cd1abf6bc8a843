#pragma once

// Mean and percentile of a set of figures (colour differences, seam steps), one rule for every
// report: the seam measure, the soft-proof check and the profile check.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numeric>
#include <vector>

namespace tilejet::colour {

struct Summary {
    size_t count = 0;
    double mean = 0;
    double percentile = 0;  // at the fraction asked for, by the nearest-rank rule
    double max = 0;
};

// The nearest-rank percentile: the smallest of `values` that at least a fraction `p` of them
// (0 < p <= 1) do not exceed, the (ceil(p n))-th smallest. Always one of the values, never
// interpolated; the 95th percentile of 20 values is the 19th smallest. 0 for no values.
// Reorders `values`.
template <typename T>
double percentile(std::vector<T>& values, double p) {
    if (values.empty()) return 0;
    const double n = double(values.size());
    const double rank = std::clamp(std::ceil(std::clamp(p, 0.0, 1.0) * n), 1.0, n);
    const auto k = values.begin() + std::ptrdiff_t(rank - 1);
    std::nth_element(values.begin(), k, values.end());
    return double(*k);
}

// Count, mean, nearest-rank percentile at `p` and maximum of `values`; all 0 for none.
// Reorders `values`.
template <typename T>
Summary summarize(std::vector<T>& values, double p) {
    Summary s;
    s.count = values.size();
    if (values.empty()) return s;
    s.mean = std::accumulate(values.begin(), values.end(), 0.0) / double(values.size());
    s.max = double(*std::max_element(values.begin(), values.end()));
    s.percentile = percentile(values, p);
    return s;
}

}  // namespace tilejet::colour
