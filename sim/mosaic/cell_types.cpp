#include "sim/mosaic/cell_types.h"

#include <stdexcept>

namespace pelage::sim {

CellTypes::CellTypes(std::vector<CellType> types,
                     std::vector<std::vector<double>> mutation,
                     std::vector<std::vector<double>> alpha)
    : m_types(std::move(types)) {
    const size_t n = m_types.size();
    if (n == 0 || n > max_cell_types || mutation.size() != n || alpha.size() != n)
        throw std::invalid_argument("CellTypes: inconsistent sizes");
    for (size_t i = 0; i < n; ++i) {
        if (mutation[i].size() != n || alpha[i].size() != n)
            throw std::invalid_argument("CellTypes: matrices must be square");
        for (size_t j = 0; j < n; ++j) {
            m_mutation[i][j] = mutation[i][j];
            m_one_minus_alpha[i][j] = 1.0 - alpha[i][j];
        }
    }
}

int CellTypes::mutate(int parent, double u) const {
    double cdf = 0;
    for (int c = 0; c < size(); ++c) {
        cdf += m_mutation[parent][c];
        if (u < cdf) return c;
    }
    return parent;  // rounding left the row sum just below u: no mutation
}

int CellTypes::find(const std::string &name) const {
    for (int c = 0; c < size(); ++c)
        if (m_types[c].name == name) return c;
    return -1;
}

int CellTypes::foreground() const {
    const int f = find("F");
    return f >= 0 ? f : (size() > 0 ? 0 : -1);
}

int CellTypes::background() const {
    const int b = find("B");
    return b >= 0 ? b : (size() > 1 ? 1 : -1);
}

}  // namespace pelage::sim
