#include "lines/rank_scores.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace penink {

std::vector<float> visible_percentiles(const std::vector<float>& values, float hidden) {
    std::vector<std::size_t> order;
    order.reserve(values.size());
    for (std::size_t i = 0; i < values.size(); ++i)
        if (values[i] != hidden) order.push_back(i);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
    std::vector<float> out(values);
    const double n = double(order.size());
    for (std::size_t lo = 0; lo < order.size();) {
        std::size_t hi = lo;
        while (hi < order.size() && values[order[hi]] == values[order[lo]]) ++hi;
        const float p = float((double(lo) + 0.5 * double(hi - lo)) / n);  // below + half the equal ones
        for (std::size_t k = lo; k < hi; ++k) out[order[k]] = p;
        lo = hi;
    }
    return out;
}

std::vector<float> rank_scores(const std::array<std::vector<float>, 3>& terms, const std::vector<float>& minus_rs_min,
                               const std::array<double, 3>& weights, float hidden) {
    for (int k = 0; k < 3; ++k)
        if (weights[k] != 0.0 && terms[k].size() != minus_rs_min.size())
            throw std::invalid_argument("rank_scores: term arrays differ in length");
    const double sum = std::accumulate(weights.begin(), weights.end(), 0.0);
    const double divisor = sum > 0.0 ? sum : 1.0;
    std::vector<float> out(minus_rs_min.size(), hidden);
    std::array<std::vector<float>, 3> ranks;
    for (int k = 0; k < 3; ++k)
        if (weights[k] != 0.0) ranks[k] = visible_percentiles(terms[k], hidden);
    for (std::size_t i = 0; i < out.size(); ++i) {
        if (minus_rs_min[i] == hidden) continue;
        double mean = 0.0;
        for (int k = 0; k < 3; ++k)
            if (weights[k] != 0.0) mean += weights[k] * ranks[k][i];
        out[i] = float(mean / divisor + minus_rs_min[i]);
    }
    return out;
}

}  // namespace penink
