#include "renderer/image/frame_pattern.h"

#include <algorithm>
#include <cctype>

namespace pelage::renderer {

namespace {

constexpr int max_width = 10;  // an int has at most 10 digits

bool is_digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

// The whole run of digits at s[*e...], advancing *e past it. Any run above max_width
// reads as max_width + 1, so a long width is refused rather than cut short or overflowed.
int read_width(const std::string &s, size_t *e) {
    int w = 0;
    for (; *e < s.size() && is_digit(s[*e]); ++*e)
        w = std::min(10 * w + (s[*e] - '0'), max_width + 1);
    return w;
}

// A placeholder starting at `at`: its length and width, or length 0 when there is none.
struct Token {
    size_t length = 0;
    int width = 1;
};

Token token_at(const std::string &s, size_t at) {
    Token t;
    if (s[at] == '#') {
        size_t e = at;
        while (e < s.size() && s[e] == '#') ++e;
        t.length = e - at;
        t.width = int(std::min(t.length, size_t(max_width + 1)));
        return t;
    }
    if (s[at] == '%') {  // %d or %0Nd
        if (s.compare(at, 2, "%d") == 0) return {2, 1};
        if (at + 1 >= s.size() || s[at + 1] != '0') return t;
        size_t e = at + 2;
        const int w = read_width(s, &e);
        if (e == at + 2 || e >= s.size() || s[e] != 'd') return t;
        return {e + 1 - at, w};
    }
    if (s.compare(at, 2, "$F") == 0) {  // $F or $FN
        size_t e = at + 2;
        const int w = read_width(s, &e);
        return {e - at, e == at + 2 ? 1 : w};
    }
    return t;
}

}  // namespace

std::optional<FramePattern> parse_frame_pattern(const std::string &text) {
    // Scan forward so a run of '#' is read whole, keep the last placeholder found.
    std::optional<FramePattern> found;
    for (size_t i = 0; i < text.size();) {
        const Token t = token_at(text, i);
        if (t.length == 0) {
            ++i;
            continue;
        }
        found = FramePattern{text.substr(0, i), text.substr(i + t.length),
                             text.substr(i, t.length), t.width};
        i += t.length;
    }
    if (found && (found->width < 1 || found->width > max_width)) return std::nullopt;
    return found;
}

std::string format_frame(const FramePattern &p, int frame) {
    const std::string num = std::to_string(frame);
    const size_t width = size_t(p.width);
    return p.head +
           (num.size() >= width ? num : std::string(width - num.size(), '0') + num) +
           p.tail;
}

std::optional<int> match_frame(const FramePattern &p, const std::string &text) {
    if (text.size() <= p.head.size() + p.tail.size() ||
        text.compare(0, p.head.size(), p.head) != 0 ||
        text.compare(text.size() - p.tail.size(), p.tail.size(), p.tail) != 0)
        return std::nullopt;
    const std::string digits =
        text.substr(p.head.size(), text.size() - p.head.size() - p.tail.size());
    if (digits.size() > size_t(max_width)) return std::nullopt;
    long long n = 0;
    for (char c : digits) {
        if (!is_digit(c)) return std::nullopt;
        n = 10 * n + (c - '0');
    }
    if (n > 2147483647LL) return std::nullopt;
    // Only the spelling format_frame writes: cow.00007.exr is not frame 7 of
    // cow.####.exr.
    if (format_frame(p, int(n)) != text) return std::nullopt;
    return int(n);
}

bool has_frame_token(const std::string &name) {
    return parse_frame_pattern(name).has_value();
}

std::string substitute_frame(const std::string &name, int frame) {
    const auto p = parse_frame_pattern(name);
    return p ? format_frame(*p, frame) : name;
}

}  // namespace pelage::renderer
