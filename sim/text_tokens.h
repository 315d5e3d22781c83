// Splitting a line of a text format (OFF, OBJ) into whitespace-separated tokens.
#pragma once

#include <cctype>
#include <string_view>
#include <vector>

namespace pelage::sim {

inline void split_whitespace(std::string_view s, std::vector<std::string_view> &out) {
    out.clear();
    size_t i = 0;
    while (i < s.size()) {
        while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
        size_t j = i;
        while (j < s.size() && !std::isspace(static_cast<unsigned char>(s[j]))) ++j;
        if (j > i) out.push_back(s.substr(i, j - i));
        i = j;
    }
}

}  // namespace pelage::sim
