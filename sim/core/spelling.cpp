#include "sim/core/spelling.h"

#include <algorithm>
#include <cctype>

namespace pelage::sim {

size_t edit_distance(const std::string &a, const std::string &b) {
    // d[i][j]: edits from the first i characters of a to the first j of b.
    const size_t n = a.size(), m = b.size();
    std::vector<std::vector<size_t>> d(n + 1, std::vector<size_t>(m + 1));
    for (size_t i = 0; i <= n; ++i) d[i][0] = i;
    for (size_t j = 0; j <= m; ++j) d[0][j] = j;
    for (size_t i = 1; i <= n; ++i) {
        for (size_t j = 1; j <= m; ++j) {
            const size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
            d[i][j] =
                std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    }
    return d[n][m];
}

std::string closest_name(const std::string &typed,
                         const std::vector<std::string> &names) {
    // A name that differs only in case is what was meant ('b' for 'B', not 'F').
    auto folded = [](std::string s) {
        for (char &c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
        return s;
    };
    for (const std::string &name : names)
        if (name != typed && folded(name) == folded(typed)) return name;
    std::string best;
    size_t best_distance = 0;
    for (const std::string &name : names) {
        const size_t distance = edit_distance(typed, name);
        if (distance > std::max<size_t>(1, name.size() / 3)) continue;
        if (best.empty() || distance < best_distance) {
            best = name;
            best_distance = distance;
        }
    }
    return best;
}

}  // namespace pelage::sim
