// Reading line-oriented text formats (OFF, OBJ): bounded line reads, so a hostile file
// with a gigabyte-long line cannot make us allocate a gigabyte, and whitespace tokens.
#pragma once

#include <cctype>
#include <istream>
#include <string>
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

// No real mesh line comes near this: 1 MiB holds a polygon of ~100k corners.
inline constexpr size_t max_line_bytes = 1u << 20;

enum class LineRead { ok, end_of_file, too_long };

// std::getline with a cap: reads up to '\n' (dropping a trailing '\r'); stops with
// too_long once the line exceeds max_bytes.
inline LineRead read_line(std::istream &in, std::string &line,
                          size_t max_bytes = max_line_bytes) {
    line.clear();
    std::streambuf *buf = in.rdbuf();
    bool any = false;
    for (;;) {
        const int c = buf->sbumpc();
        if (c == std::char_traits<char>::eof()) {
            in.setstate(std::ios::eofbit);
            return any ? LineRead::ok : LineRead::end_of_file;
        }
        any = true;
        if (c == '\n') break;
        if (line.size() >= max_bytes) return LineRead::too_long;
        line.push_back(static_cast<char>(c));
    }
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return LineRead::ok;
}

}  // namespace pelage::sim
