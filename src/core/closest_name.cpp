#include "core/closest_name.hpp"

#include <algorithm>

namespace penink {

std::size_t edit_distance(const std::string& a, const std::string& b) {
    const std::size_t n = a.size(), m = b.size();
    std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
    for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
    for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
    for (std::size_t i = 1; i <= n; ++i)
        for (std::size_t j = 1; j <= m; ++j) {
            const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[n][m];
}

std::string closest_name(const std::string& name, const std::vector<std::string>& known) {
    if (name.size() > 64) return "";  // no one misspells that much
    std::string best;
    std::size_t best_d = 3;
    for (const std::string& k : known) {
        const std::size_t d = edit_distance(name, k);
        if (d < best_d && 2 * d < std::max(name.size(), k.size())) best = k, best_d = d;
    }
    return best;
}

std::string did_you_mean(const std::string& name, const std::vector<std::string>& known) {
    const std::string c = closest_name(name, known);
    return c.empty() ? "" : "; did you mean " + c + "?";
}

}  // namespace penink
