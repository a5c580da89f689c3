#include "lines/crease_scores.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace penink {

float max_visible_distance(const DepthImage& toward) {
    float d = 0.0f;
    for (float t : toward.depth)
        if (std::isfinite(t)) d = std::max(d, t);
    return d;
}

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

std::vector<float> crease_scores(std::span<const CreaseTerms> terms, const CreaseParams& p, float max_distance) {
    const std::array<double, 3> weights{p.slope_weight, p.illumination_weight, p.flow_weight};
    const double sum = weights[0] + weights[1] + weights[2];
    const double divisor = p.normalisation == ScoreNormalisation::thirds ? 3.0 : sum > 0.0 ? sum : 1.0;
    const float min_score = float(p.min_score), attenuation = float(p.distance_attenuation);
    const float D = std::max(max_distance, 1e-6f);
    const auto rs_min = [&](const CreaseTerms& t) { return min_score + attenuation * t.distance / D; };
    std::vector<float> out(terms.size(), dm_hidden);
    if (p.normalisation != ScoreNormalisation::rank) {
        const float sw = float(weights[0]), iw = float(weights[1]), fw = float(weights[2]), div = float(divisor);
        for (std::size_t i = 0; i < terms.size(); ++i) {
            const CreaseTerms& t = terms[i];
            if (t.distance != dm_hidden)
                out[i] = (sw * t.slope + iw * t.illumination + fw * t.flow) / div - rs_min(t);
        }
        return out;
    }
    std::array<std::vector<float>, 3> ranks;  // empty where the weight is 0 (not ranked)
    for (int k = 0; k < 3; ++k) {
        if (weights[k] == 0.0) continue;
        std::vector<float> term(terms.size(), dm_hidden);
        for (std::size_t i = 0; i < terms.size(); ++i)
            if (terms[i].distance != dm_hidden)
                term[i] = k == 0 ? terms[i].slope : k == 1 ? terms[i].illumination : terms[i].flow;
        ranks[k] = visible_percentiles(term, dm_hidden);
    }
    for (std::size_t i = 0; i < out.size(); ++i) {
        if (terms[i].distance == dm_hidden) continue;
        double mean = 0.0;
        for (int k = 0; k < 3; ++k)
            if (weights[k] != 0.0) mean += weights[k] * ranks[k][i];
        out[i] = float(mean / divisor + double(-rs_min(terms[i])));
    }
    return out;
}

}  // namespace penink
