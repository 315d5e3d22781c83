// Union–find over 0 … n−1 with path halving. The lower index becomes the root of a
// union, so the sets' representatives do not depend on the order of the unions.
#pragma once

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

namespace pelage::sim {

class DisjointSets {
  public:
    explicit DisjointSets(size_t n) : m_parent(n) {
        std::iota(m_parent.begin(), m_parent.end(), 0u);
    }
    uint32_t find(uint32_t a) {
        while (m_parent[a] != a) a = m_parent[a] = m_parent[m_parent[a]];
        return a;
    }
    void unite(uint32_t a, uint32_t b) {
        a = find(a);
        b = find(b);
        if (a != b) m_parent[std::max(a, b)] = std::min(a, b);
    }

  private:
    std::vector<uint32_t> m_parent;
};

}  // namespace pelage::sim
