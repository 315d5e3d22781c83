#include "renderer/export/usda_writer.h"

#include <charconv>
#include <cmath>
#include <stdexcept>

namespace pelage::renderer {

std::string usd_identifier(std::string_view name) {
    std::string s;
    for (char c : name) {
        const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                        (c >= '0' && c <= '9') || c == '_';
        s += ok ? c : '_';
    }
    if (s.empty() || (s[0] >= '0' && s[0] <= '9')) s.insert(s.begin(), '_');
    return s;
}

void UsdaWriter::flush() {
    m_out.write(m_buffer.data(), std::streamsize(m_buffer.size()));
    m_buffer.clear();
}

void UsdaWriter::indent() { m_buffer.append(size_t(4 * m_depth), ' '); }

void UsdaWriter::line(std::string_view text) {
    indent();
    put(text);
    put("\n");
    maybe_flush();
}

void UsdaWriter::begin_prim(std::string_view type, std::string_view name,
                            const std::vector<std::string> &metadata) {
    indent();
    put("def ");
    put(type);
    put(" \"");
    put(name);
    put("\"\n");
    if (!metadata.empty()) {
        line("(");
        ++m_depth;
        for (const std::string &m : metadata) line(m);
        --m_depth;
        line(")");
    }
    line("{");
    ++m_depth;
}

void UsdaWriter::end_prim() {
    --m_depth;
    line("}");
}

void UsdaWriter::number(float v) {
    // USD reads inf and nan as such; pelage never writes them (the data is checked).
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    m_buffer.append(buf, r.ptr);
}

void UsdaWriter::number(double v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    m_buffer.append(buf, r.ptr);
}

void UsdaWriter::number(int32_t v) {
    char buf[16];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    m_buffer.append(buf, r.ptr);
}

void UsdaWriter::values(const float *v, size_t count, int tuple) {
    put("[");
    for (size_t i = 0; i < count; ++i) {
        if (i) put(", ");
        if (tuple > 1) put("(");
        for (int k = 0; k < tuple; ++k) {
            if (k) put(", ");
            const float x = v[i * size_t(tuple) + size_t(k)];
            if (!std::isfinite(x))
                throw std::runtime_error("a value to export is not finite");
            number(x);
        }
        if (tuple > 1) put(")");
        if ((i & 1023) == 1023) maybe_flush();
    }
    put("]");
}

void UsdaWriter::values(const int32_t *v, size_t count) {
    put("[");
    for (size_t i = 0; i < count; ++i) {
        if (i) put(", ");
        number(v[i]);
        if ((i & 1023) == 1023) maybe_flush();
    }
    put("]");
}

void UsdaWriter::interpolation(std::string_view interp) {
    if (interp.empty()) return;
    put(" (\n");
    ++m_depth;
    indent();
    put("interpolation = \"");
    put(interp);
    put("\"\n");
    --m_depth;
    indent();
    put(")");
}

void UsdaWriter::array(std::string_view decl, const float *v, size_t count, int tuple,
                       std::string_view interp) {
    indent();
    put(decl);
    put(" = ");
    values(v, count, tuple);
    interpolation(interp);
    put("\n");
    maybe_flush();
}

void UsdaWriter::array(std::string_view decl, const int32_t *v, size_t count,
                       std::string_view interp) {
    indent();
    put(decl);
    put(" = ");
    values(v, count);
    interpolation(interp);
    put("\n");
    maybe_flush();
}

void UsdaWriter::begin_time_samples(std::string_view decl, std::string_view interp) {
    if (!interp.empty()) {
        indent();
        put(decl);
        interpolation(interp);
        put("\n");
    }
    indent();
    put(decl);
    put(".timeSamples = {\n");
    ++m_depth;
}

void UsdaWriter::sample(double time, const float *v, size_t count, int tuple) {
    indent();
    number(time);
    put(": ");
    values(v, count, tuple);
    put(",\n");
    maybe_flush();
}

void UsdaWriter::sample(double time, const int32_t *v, size_t count) {
    indent();
    number(time);
    put(": ");
    values(v, count);
    put(",\n");
    maybe_flush();
}

void UsdaWriter::matrix_value(const double m[16]) {
    put("( ");
    for (int r = 0; r < 4; ++r) {
        if (r) put(", ");
        put("(");
        for (int c = 0; c < 4; ++c) {
            if (c) put(", ");
            number(m[4 * r + c]);
        }
        put(")");
    }
    put(" )");
}

void UsdaWriter::sample_matrix(double time, const double m[16]) {
    indent();
    number(time);
    put(": ");
    matrix_value(m);
    put(",\n");
}

void UsdaWriter::end_time_samples() {
    --m_depth;
    indent();
    put("}\n");
    maybe_flush();
}

void UsdaWriter::matrix(std::string_view decl, const double m[16]) {
    indent();
    put(decl);
    put(" = ");
    matrix_value(m);
    put("\n");
}

}  // namespace pelage::renderer
