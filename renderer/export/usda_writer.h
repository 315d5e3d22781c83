// OpenUSD's text format (.usda), written as a stream: the layer's header and
// metadata, nested prims, and attributes whose values are scalars, arrays of scalars or
// of tuples (point3f[], texCoord2f[], ...), either one value or time samples. The
// grammar is the one of Pixar's USD specification ("USDA file format"): arrays as
// [v, v, ...], tuples as (x, y, z), time samples as {t: value, ...}. Floats are written
// in their shortest form that reads back to the same float (std::to_chars), so a
// reader gets exactly the values pelage holds.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace pelage::renderer {

// A prim name: letters, digits and '_', not starting with a digit (USD's identifier
// rule); other characters become '_', and an empty name becomes "_".
std::string usd_identifier(std::string_view name);

class UsdaWriter {
  public:
    explicit UsdaWriter(std::ostream &out) : m_out(out) {}
    ~UsdaWriter() { flush(); }
    UsdaWriter(const UsdaWriter &) = delete;
    UsdaWriter &operator=(const UsdaWriter &) = delete;

    // One line at the current depth (its text as given: declarations, metadata).
    void line(std::string_view text);
    // `def TYPE "NAME" (METADATA) {`; metadata lines without the parentheses.
    void begin_prim(std::string_view type, std::string_view name,
                    const std::vector<std::string> &metadata = {});
    void end_prim();

    // `DECL = [values]` with `tuple` numbers per element ((x, y) for 2, (x, y, z) for
    // 3), then `(interpolation = "INTERP")` when given.
    void array(std::string_view decl, const float *values, size_t count, int tuple,
               std::string_view interpolation = {});
    void array(std::string_view decl, const int32_t *values, size_t count,
               std::string_view interpolation = {});
    // `DECL.timeSamples = { t: [values], ... }`: begin, one sample per time, end. The
    // interpolation, when given, is declared first (`DECL (interpolation = ...)`), as
    // metadata belongs to the declaration.
    void begin_time_samples(std::string_view decl, std::string_view interpolation = {});
    void sample(double time, const float *values, size_t count, int tuple);
    void sample(double time, const int32_t *values, size_t count);
    void sample_matrix(double time, const double m[16]);
    void end_time_samples();
    // `DECL = ( (row), (row), (row), (row) )`: a 4×4 matrix, rows as USD stores them.
    void matrix(std::string_view decl, const double m[16]);

    void flush();

  private:
    void indent();
    void put(std::string_view s) { m_buffer.append(s); }
    void number(float v);
    void number(double v);
    void number(int32_t v);
    void values(const float *v, size_t count, int tuple);
    void values(const int32_t *v, size_t count);
    void matrix_value(const double m[16]);
    void interpolation(std::string_view interp);
    void maybe_flush() {
        if (m_buffer.size() > (1u << 20)) flush();
    }

    std::ostream &m_out;
    std::string m_buffer;
    int m_depth = 0;
};

}  // namespace pelage::renderer
