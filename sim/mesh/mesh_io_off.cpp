// OFF reader (Geomview's Object File Format, as shipped by CGAL's sample data).
// Accepts OFF/COFF/NOFF/CNOFF/STOFF headers, '#' comments, counts on the header line,
// per-vertex extras (normals, colours) and per-face colours, which are ignored.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <string_view>
#include <vector>

#include "sim/core/input_error.h"
#include "sim/core/text_lines.h"
#include "sim/mesh/mesh_io.h"

namespace pelage::sim {
namespace {

class LineTokens {
  public:
    LineTokens(const std::string &path, std::istream &in) : m_path(path), m_in(in) {}

    // Reads the next line that holds at least one token; false at end of file.
    bool next_line() {
        for (;;) {
            const LineRead r = read_line(m_in, m_line);
            if (r == LineRead::end_of_file) break;
            ++m_line_no;
            if (r == LineRead::too_long)
                fail("line longer than " + std::to_string(max_line_bytes) + " bytes");
            if (auto hash = m_line.find('#'); hash != std::string::npos)
                m_line.resize(hash);
            split_whitespace(m_line, m_tokens);
            if (!m_tokens.empty()) return true;
        }
        return false;
    }

    const std::vector<std::string_view> &tokens() const { return m_tokens; }
    size_t line_no() const { return m_line_no; }

    [[noreturn]] void fail(const std::string &message) const {
        throw InputError(m_path, m_line_no, "", message);
    }

    double number(size_t i, const char *what) const {
        const std::string_view tok = m_tokens.at(i);
        double v = 0;
        const auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
        if (ec != std::errc() || end != tok.data() + tok.size())
            fail(std::string("malformed ") + what + " '" + std::string(tok) + "'");
        if (!std::isfinite(v))
            fail(std::string("non-finite ") + what + " '" + std::string(tok) + "'");
        return v;
    }

    uint64_t count(size_t i, const char *what) const {
        const std::string_view tok = m_tokens.at(i);
        uint64_t v = 0;
        const auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
        if (ec != std::errc() || end != tok.data() + tok.size())
            fail(std::string("malformed ") + what + " '" + std::string(tok) +
                 "' (expected a non-negative integer)");
        return v;
    }

  private:
    const std::string &m_path;
    std::istream &m_in;
    std::string m_line;
    std::vector<std::string_view> m_tokens;
    size_t m_line_no = 0;
};

bool is_off_keyword(std::string_view t) {
    // [ST][C][N][4][n]OFF: we accept the 3D variants only.
    return t == "OFF" || t == "COFF" || t == "NOFF" || t == "CNOFF" || t == "STOFF" ||
           t == "STCOFF" || t == "STNOFF" || t == "STCNOFF";
}

}  // namespace

TriangleMesh read_off(const std::string &path, MeshReadStats *stats) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, 0, "", "cannot open file");
    in.seekg(0, std::ios::end);
    const auto file_bytes =
        static_cast<uint64_t>(std::max<std::streamoff>(in.tellg(), 0));
    in.seekg(0);

    LineTokens lines(path, in);
    if (!lines.next_line())
        throw InputError(path, 0, "", "empty file (expected an OFF header)");

    // --- Header: keyword, then "nv nf ne" on the same or the next line ---
    size_t first = 0;  // index of the vertex count among this line's tokens
    if (is_off_keyword(lines.tokens()[0])) {
        first = 1;
        if (lines.tokens().size() == 1) {
            if (!lines.next_line())
                lines.fail("truncated header: expected vertex, face and edge counts");
            first = 0;
        }
    } else if (lines.tokens()[0].find("OFF") != std::string_view::npos) {
        lines.fail("unsupported OFF variant '" + std::string(lines.tokens()[0]) + "'");
    } else {
        lines.fail("not an OFF file: expected the keyword 'OFF', found '" +
                   std::string(lines.tokens()[0]) + "'");
    }
    if (lines.tokens().size() < first + 2)
        lines.fail("malformed header: expected vertex, face and edge counts");
    const uint64_t nv = lines.count(first, "vertex count");
    const uint64_t nf = lines.count(first + 1, "face count");
    if (nv == 0 || nf == 0)
        lines.fail("empty mesh: the header declares no vertices or faces");
    // Every vertex and face needs at least a few bytes: a header that claims more than
    // the file can hold is corrupt, and must not make us allocate for it.
    if (nv > file_bytes / 2 || nf > file_bytes / 2)
        lines.fail("header declares " + std::to_string(nv) + " vertices and " +
                   std::to_string(nf) + " faces, more than a file of " +
                   std::to_string(file_bytes) + " bytes can hold");

    TriangleMesh mesh;
    mesh.positions.reserve(nv);
    mesh.triangles.reserve(nf);
    mesh.source_face.reserve(nf);

    // --- Vertices: x y z [extras] ---
    for (uint64_t v = 0; v < nv; ++v) {
        if (!lines.next_line())
            lines.fail("truncated file: expected " + std::to_string(nv) +
                       " vertices, found " + std::to_string(v));
        if (lines.tokens().size() < 3)
            lines.fail("malformed vertex " + std::to_string(v) +
                       ": expected 3 coordinates");
        mesh.positions.push_back({lines.number(0, "coordinate"),
                                  lines.number(1, "coordinate"),
                                  lines.number(2, "coordinate")});
    }

    // --- Faces: n i0 .. i(n-1) [colour], polygons fanned from corner 0 ---
    for (uint64_t f = 0; f < nf; ++f) {
        if (!lines.next_line())
            lines.fail("truncated file: expected " + std::to_string(nf) +
                       " faces, found " + std::to_string(f));
        const uint64_t n = lines.count(0, "face corner count");
        if (n < 3)
            lines.fail("face " + std::to_string(f) + " has " + std::to_string(n) +
                       " corners (a face needs at least 3)");
        if (n > lines.tokens().size() - 1)  // not `size < n + 1`: n + 1 wraps at 2^64 - 1
            lines.fail("malformed face " + std::to_string(f) + ": declares " +
                       std::to_string(n) + " corners, lists " +
                       std::to_string(lines.tokens().size() - 1));
        std::vector<VertId> corners(n);
        for (uint64_t c = 0; c < n; ++c) {
            const uint64_t idx = lines.count(1 + c, "vertex index");
            if (idx >= nv)
                lines.fail("vertex index " + std::to_string(idx) + " out of range [0, " +
                           std::to_string(nv) + ")");
            corners[c] = static_cast<VertId>(idx);
        }
        for (uint64_t c = 1; c + 1 < n; ++c) {
            mesh.triangles.push_back({corners[0], corners[c], corners[c + 1]});
            mesh.source_face.push_back(static_cast<uint32_t>(f));
        }
        if (n > 3 && stats) ++stats->polygons_triangulated;
    }
    return mesh;
}

}  // namespace pelage::sim
