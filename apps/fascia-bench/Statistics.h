#pragma once
/// The order statistics fascia-bench reports (docs/performance.md, Method).
#include <algorithm>
#include <cstddef>
#include <vector>

namespace fascia::bench {

/// The q-quantile of v (0 <= q <= 1): the sample with floor(q n) samples below it in sorted order,
/// the largest for q = 1 (so the median of an even count is the upper of the middle two); 0 for none.
inline double quantile(std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    const size_t k = std::min(v.size() - 1, static_cast<size_t>(q * double(v.size())));
    std::nth_element(v.begin(), v.begin() + long(k), v.end());
    return v[k];
}

inline double median(const std::vector<double>& v) { return quantile(v, 0.5); }

/// Single steps (or groups of steps, per step) of a case: their median, 90th and 99th percentiles.
struct StepStats {
    double median = 0, p90 = 0, p99 = 0;
};

inline StepStats stepStats(const std::vector<double>& v) { return {quantile(v, 0.5), quantile(v, 0.9), quantile(v, 0.99)}; }

} // namespace fascia::bench
