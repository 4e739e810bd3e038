#include "benchkit/results.hpp"

#include <algorithm>
#include <cmath>

namespace glcollide::benchkit {

namespace {
/// The q-quantile of sorted samples, interpolating linearly between neighbours (type 7).
double quantile(const std::vector<double>& sorted, double q) {
    const double position = q * static_cast<double>(sorted.size() - 1);
    const auto below = static_cast<std::size_t>(std::floor(position));
    const std::size_t above = std::min(below + 1, sorted.size() - 1);
    const double t = position - static_cast<double>(below);
    return sorted[below] + t * (sorted[above] - sorted[below]);
}
} // namespace

Summary summarize(std::vector<double> samples) {
    Summary s;
    if (samples.empty()) return s;
    std::sort(samples.begin(), samples.end());
    s.samples = samples.size();
    s.min = samples.front();
    s.max = samples.back();
    s.median = quantile(samples, 0.5);
    s.q1 = quantile(samples, 0.25);
    s.q3 = quantile(samples, 0.75);
    return s;
}

double RunResult::metric(const std::string& key, double fallback) const {
    for (const Metric& m : metrics)
        if (m.key == key) return m.value;
    return fallback;
}

void RunResult::set(const std::string& key, double value) {
    for (Metric& m : metrics)
        if (m.key == key) {
            m.value = value;
            return;
        }
    metrics.push_back({key, value});
}

} // namespace glcollide::benchkit
