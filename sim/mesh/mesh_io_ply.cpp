// PLY reader (Turk's Polygon File Format: ASCII, binary little- and big-endian). pelage
// reads PLY itself rather than through assimp: assimp 5.2's PLY importer crashes or
// hangs on many damaged headers, and a reader of our own can name the line (ASCII) or
// the element (binary) at fault. Every element of the header is read; `vertex` gives
// x, y, z and, when present, nx, ny, nz and u, v (also s, t and texture_u, texture_v);
// `face` gives a list `vertex_indices` (or `vertex_index`), fanned into triangles.
// The vertex's other scalar properties are kept by name as vertex attributes (painted
// masks, weights: TriangleMesh::vertex_attributes). Other elements are skipped.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <string_view>
#include <vector>

#include "sim/core/input_error.h"
#include "sim/core/text_lines.h"
#include "sim/mesh/mesh_io.h"

namespace pelage::sim {
namespace {

enum class Scalar { i8, u8, i16, u16, i32, u32, f32, f64 };

bool parse_scalar(std::string_view t, Scalar *s) {
    static const struct {
        const char *name;
        Scalar s;
    } names[] = {
        {"char", Scalar::i8},    {"int8", Scalar::i8},     {"uchar", Scalar::u8},
        {"uint8", Scalar::u8},   {"short", Scalar::i16},   {"int16", Scalar::i16},
        {"ushort", Scalar::u16}, {"uint16", Scalar::u16},  {"int", Scalar::i32},
        {"int32", Scalar::i32},  {"uint", Scalar::u32},    {"uint32", Scalar::u32},
        {"float", Scalar::f32},  {"float32", Scalar::f32}, {"double", Scalar::f64},
        {"float64", Scalar::f64}};
    for (const auto &n : names)
        if (t == n.name) {
            *s = n.s;
            return true;
        }
    return false;
}

size_t scalar_bytes(Scalar s) {
    switch (s) {
        case Scalar::i8:
        case Scalar::u8:
            return 1;
        case Scalar::i16:
        case Scalar::u16:
            return 2;
        case Scalar::i32:
        case Scalar::u32:
        case Scalar::f32:
            return 4;
        case Scalar::f64:
            return 8;
    }
    return 1;
}

bool is_integer(Scalar s) { return s != Scalar::f32 && s != Scalar::f64; }

struct Property {
    std::string name;
    Scalar type = Scalar::f32;
    bool list = false;
    Scalar count_type = Scalar::u8;  // list only
};

struct Element {
    std::string name;
    uint64_t count = 0;
    std::vector<Property> props;
};

enum class Format { ascii, binary_le, binary_be };

struct Header {
    Format format = Format::ascii;
    std::vector<Element> elements;
    size_t lines = 0;  // the line of end_header
};

Header read_header(const std::string &path, std::istream &in, uint64_t file_bytes) {
    Header h;
    std::string line;
    std::vector<std::string_view> tok;
    size_t line_no = 0;
    auto fail = [&](const std::string &msg) { throw InputError(path, line_no, "", msg); };
    auto next = [&]() {
        const LineRead r = read_line(in, line);
        ++line_no;
        if (r == LineRead::end_of_file) fail("truncated header: no end_header line");
        if (r == LineRead::too_long)
            fail("line longer than " + std::to_string(max_line_bytes) + " bytes");
        split_whitespace(line, tok);
    };
    next();
    if (tok.size() != 1 || tok[0] != "ply")
        fail("not a PLY file: expected the keyword 'ply' on the first line");
    bool have_format = false;
    for (;;) {
        next();
        if (tok.empty()) continue;
        if (tok[0] == "comment" || tok[0] == "obj_info") continue;
        if (tok[0] == "end_header") break;
        if (tok[0] == "format") {
            if (tok.size() != 3 || tok[2] != "1.0")
                fail(
                    "malformed format line: expected 'format ascii 1.0' (or "
                    "binary_little_endian, binary_big_endian)");
            if (tok[1] == "ascii")
                h.format = Format::ascii;
            else if (tok[1] == "binary_little_endian")
                h.format = Format::binary_le;
            else if (tok[1] == "binary_big_endian")
                h.format = Format::binary_be;
            else
                fail("unknown PLY format '" + std::string(tok[1]) + "'");
            have_format = true;
        } else if (tok[0] == "element") {
            if (tok.size() != 3)
                fail("malformed element line: expected 'element NAME COUNT'");
            Element e;
            e.name = tok[1];
            const auto [end, ec] =
                std::from_chars(tok[2].data(), tok[2].data() + tok[2].size(), e.count);
            if (ec != std::errc() || end != tok[2].data() + tok[2].size())
                fail("malformed element count '" + std::string(tok[2]) + "'");
            // Every row takes at least one byte: a count beyond the file is corrupt and
            // must not make us allocate for it.
            if (e.count > file_bytes)
                fail("element '" + e.name + "' declares " + std::to_string(e.count) +
                     " rows, more than a file of " + std::to_string(file_bytes) +
                     " bytes can hold");
            h.elements.push_back(std::move(e));
        } else if (tok[0] == "property") {
            if (h.elements.empty()) fail("property before any element");
            Property p;
            if (tok.size() == 5 && tok[1] == "list") {
                p.list = true;
                if (!parse_scalar(tok[2], &p.count_type) || !is_integer(p.count_type))
                    fail("malformed list count type '" + std::string(tok[2]) + "'");
                if (!parse_scalar(tok[3], &p.type))
                    fail("unknown property type '" + std::string(tok[3]) + "'");
                p.name = tok[4];
            } else if (tok.size() == 3) {
                if (!parse_scalar(tok[1], &p.type))
                    fail("unknown property type '" + std::string(tok[1]) + "'");
                p.name = tok[2];
            } else {
                fail(
                    "malformed property line: expected 'property TYPE NAME' or "
                    "'property list COUNT_TYPE TYPE NAME'");
            }
            h.elements.back().props.push_back(std::move(p));
        } else {
            fail("unknown header line '" + std::string(tok[0]) + "'");
        }
    }
    if (!have_format) fail("no format line in the header");
    h.lines = line_no;
    return h;
}

// Reads the body one value at a time, as text (one row per line) or as bytes.
class BodyReader {
  public:
    BodyReader(const std::string &path, std::istream &in, Format format, size_t line_no)
        : m_path(path), m_in(in), m_format(format), m_line_no(line_no) {}

    // Starts the row `row` of element `e` (for messages); ASCII reads its line.
    void start_row(const Element &e, uint64_t row) {
        m_what = e.name + " " + std::to_string(row);
        if (m_format != Format::ascii) return;
        for (;;) {
            const LineRead r = read_line(m_in, m_line);
            if (r == LineRead::end_of_file)
                fail("truncated file: expected " + std::to_string(e.count) + " " +
                     e.name + " rows, found " + std::to_string(row));
            ++m_line_no;
            if (r == LineRead::too_long)
                fail("line longer than " + std::to_string(max_line_bytes) + " bytes");
            split_whitespace(m_line, m_tok);
            if (!m_tok.empty()) break;
        }
        m_next = 0;
    }
    // ASCII: the row must hold exactly the values read.
    void end_row() {
        if (m_format == Format::ascii && m_next != m_tok.size())
            fail(m_what + ": " + std::to_string(m_tok.size()) +
                 " values on the line, the header's properties take " +
                 std::to_string(m_next));
    }

    double value(Scalar s, const char *what) {
        if (m_format == Format::ascii) {
            if (m_next >= m_tok.size()) fail(m_what + ": too few values on the line");
            const std::string_view t = m_tok[m_next++];
            double v = 0;
            const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
            if (ec != std::errc() || end != t.data() + t.size())
                fail(m_what + ": malformed " + what + " '" + std::string(t) + "'");
            if (is_integer(s) && v != std::floor(v))
                fail(m_what + ": " + what + " '" + std::string(t) +
                     "' is not an integer");
            return v;
        }
        unsigned char b[8];
        const size_t n = scalar_bytes(s);
        if (!m_in.read(reinterpret_cast<char *>(b), std::streamsize(n)))
            fail("truncated file: the data ends inside " + m_what);
        const bool swap = (m_format == Format::binary_be) != big_endian_host();
        if (swap) std::reverse(b, b + n);
        switch (s) {
            case Scalar::i8:
                return double(int8_t(b[0]));
            case Scalar::u8:
                return double(b[0]);
            case Scalar::i16:
                return double(load<int16_t>(b));
            case Scalar::u16:
                return double(load<uint16_t>(b));
            case Scalar::i32:
                return double(load<int32_t>(b));
            case Scalar::u32:
                return double(load<uint32_t>(b));
            case Scalar::f32:
                return double(load<float>(b));
            case Scalar::f64:
                return load<double>(b);
        }
        return 0;
    }

    [[noreturn]] void fail(const std::string &msg) const {
        throw InputError(m_path, m_format == Format::ascii ? m_line_no : 0, "", msg);
    }
    const std::string &what() const { return m_what; }

  private:
    template <typename T>
    static T load(const unsigned char *b) {
        T v;
        std::memcpy(&v, b, sizeof v);
        return v;
    }
    static bool big_endian_host() {
        const uint16_t one = 1;
        unsigned char b;
        std::memcpy(&b, &one, 1);
        return b == 0;
    }

    const std::string &m_path;
    std::istream &m_in;
    Format m_format;
    size_t m_line_no;
    std::string m_line, m_what;
    std::vector<std::string_view> m_tok;
    size_t m_next = 0;
};

// Which property of the vertex element is which attribute; -1 = absent.
struct VertexLayout {
    int x = -1, y = -1, z = -1, nx = -1, ny = -1, nz = -1, u = -1, v = -1;
    std::vector<int> extra;  // every other scalar property, in header order
    bool normals() const { return nx >= 0 && ny >= 0 && nz >= 0; }
    bool uvs() const { return u >= 0 && v >= 0; }
};

VertexLayout vertex_layout(const Element &e) {
    VertexLayout l;
    for (int i = 0; i < int(e.props.size()); ++i) {
        const Property &p = e.props[size_t(i)];
        if (p.list) continue;
        const std::string &n = p.name;
        if (n == "x") l.x = i;
        if (n == "y") l.y = i;
        if (n == "z") l.z = i;
        if (n == "nx") l.nx = i;
        if (n == "ny") l.ny = i;
        if (n == "nz") l.nz = i;
        if (n == "u" || n == "s" || n == "texture_u") l.u = i;
        if (n == "v" || n == "t" || n == "texture_v") l.v = i;
    }
    for (int i = 0; i < int(e.props.size()); ++i)
        if (!e.props[size_t(i)].list && i != l.x && i != l.y && i != l.z && i != l.nx &&
            i != l.ny && i != l.nz && i != l.u && i != l.v)
            l.extra.push_back(i);
    return l;
}

}  // namespace

TriangleMesh read_ply(const std::string &path, MeshReadStats *stats) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, 0, "", "cannot open file");
    in.seekg(0, std::ios::end);
    const auto file_bytes =
        static_cast<uint64_t>(std::max<std::streamoff>(in.tellg(), 0));
    in.seekg(0);
    if (file_bytes == 0) throw InputError(path, 0, "", "empty file");
    const Header h = read_header(path, in, file_bytes);

    const Element *vertex = nullptr, *face = nullptr;
    for (const Element &e : h.elements) {
        if (e.name == "vertex" && !vertex) vertex = &e;
        if (e.name == "face" && !face) face = &e;
    }
    if (!vertex || vertex->count == 0)
        throw InputError(path, 0, "", "the file holds no triangles (no vertices)");
    const VertexLayout vl = vertex_layout(*vertex);
    if (vl.x < 0 || vl.y < 0 || vl.z < 0)
        throw InputError(path, 0, "", "the vertex element has no x, y and z properties");
    if (!face || face->count == 0)
        throw InputError(path, 0, "",
                         "the file holds no triangles (only " +
                             std::to_string(vertex->count) + " points: no faces)");
    int index_prop = -1;
    for (int i = 0; i < int(face->props.size()); ++i) {
        const Property &p = face->props[size_t(i)];
        if (p.list && (p.name == "vertex_indices" || p.name == "vertex_index") &&
            is_integer(p.type))
            index_prop = i;
    }
    if (index_prop < 0)
        throw InputError(path, 0, "",
                         "the face element has no integer list 'vertex_indices'");

    std::vector<Vec3d> normals;
    std::vector<Vec2d> uvs;
    TriangleMesh mesh;
    BodyReader body(path, in, h.format, h.lines);
    std::vector<double> row;
    std::vector<VertId> corners;
    for (const Element &e : h.elements) {
        const bool is_vertex = &e == vertex, is_face = &e == face;
        if (is_vertex) {
            // Not reserved: a damaged header may declare many properties and rows; the
            // values grow with what the file really holds.
            for (int i : vl.extra)
                mesh.vertex_attributes.push_back({e.props[size_t(i)].name, {}});
            mesh.positions.reserve(e.count);
            if (vl.normals()) normals.reserve(e.count);
            if (vl.uvs()) uvs.reserve(e.count);
        }
        for (uint64_t r = 0; r < e.count; ++r) {
            body.start_row(e, r);
            row.assign(e.props.size(), 0.0);
            for (size_t p = 0; p < e.props.size(); ++p) {
                const Property &prop = e.props[p];
                if (!prop.list) {
                    row[p] = body.value(prop.type, "value");
                    continue;
                }
                const double n = body.value(prop.count_type, "list length");
                if (n < 0 || n > double(file_bytes))
                    body.fail(body.what() + ": list length " +
                              std::to_string(int64_t(n)) +
                              " is impossible in a file of " +
                              std::to_string(file_bytes) + " bytes");
                const bool indices = is_face && int(p) == index_prop;
                if (indices) {
                    if (n < 3)
                        body.fail(body.what() + " has " + std::to_string(int64_t(n)) +
                                  " corners (a face needs at least 3)");
                    corners.clear();
                }
                for (uint64_t k = 0; k < uint64_t(n); ++k) {
                    const double idx = body.value(prop.type, "vertex index");
                    if (!indices) continue;
                    if (idx < 0 || idx >= double(vertex->count))
                        body.fail(body.what() + ": vertex index " +
                                  std::to_string(int64_t(idx)) + " out of range [0, " +
                                  std::to_string(vertex->count) + ")");
                    corners.push_back(static_cast<VertId>(idx));
                }
                if (indices) {
                    for (size_t c = 1; c + 1 < corners.size(); ++c) {
                        mesh.triangles.push_back(
                            {corners[0], corners[c], corners[c + 1]});
                        mesh.source_face.push_back(static_cast<uint32_t>(r));
                    }
                    if (stats && corners.size() > 3) ++stats->polygons_triangulated;
                }
            }
            body.end_row();
            if (!is_vertex) continue;
            const Vec3d pos{row[size_t(vl.x)], row[size_t(vl.y)], row[size_t(vl.z)]};
            if (!is_finite(pos)) body.fail(body.what() + ": non-finite coordinate");
            mesh.positions.push_back(pos);
            for (size_t a = 0; a < vl.extra.size(); ++a) {
                const double value = row[size_t(vl.extra[a])];
                if (!std::isfinite(value))
                    body.fail(body.what() + ": non-finite " +
                              mesh.vertex_attributes[a].first);
                mesh.vertex_attributes[a].second.push_back(static_cast<float>(value));
            }
            if (vl.normals()) {
                const Vec3d n{row[size_t(vl.nx)], row[size_t(vl.ny)], row[size_t(vl.nz)]};
                if (!is_finite(n)) body.fail(body.what() + ": non-finite normal");
                normals.push_back(n);
            }
            if (vl.uvs()) {
                const Vec2d t{row[size_t(vl.u)], row[size_t(vl.v)]};
                if (!std::isfinite(t.x) || !std::isfinite(t.y))
                    body.fail(body.what() + ": non-finite texture coordinate");
                uvs.push_back(t);
            }
        }
    }
    if (mesh.triangles.empty())
        throw InputError(path, 0, "", "the file holds no triangles");
    for (const auto &tri : mesh.triangles)
        for (VertId v : tri) {
            if (!normals.empty()) mesh.corner_normals.push_back(normals[v]);
            if (!uvs.empty()) mesh.corner_uvs.push_back(uvs[v]);
        }
    return mesh;
}

}  // namespace pelage::sim
