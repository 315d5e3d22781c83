// OBJ reader: tinyobjloader does the parsing and polygon triangulation. tinyobjloader is
// lenient (a malformed number reads as 0, a bad index may be skipped), so a short
// validating pass first checks the lines that define geometry and reports the first bad
// one with its line number: we never render a mesh the file did not describe.
#include <charconv>
#include <cmath>
#include <fstream>
#include <string_view>
#include <vector>

#ifndef TINYOBJLOADER_USE_DOUBLE
#define TINYOBJLOADER_USE_DOUBLE  // must match the linked libtinyobjloader_double
#endif
#include <tiny_obj_loader.h>

#include "sim/core/input_error.h"
#include "sim/core/text_lines.h"
#include "sim/mesh/mesh_io.h"

namespace pelage::sim {
namespace {

// Parses an OBJ index (1-based, or negative = relative to the `count` defined so far) and
// returns it 0-based; -1 when it names no element.
int64_t resolve_obj_index(std::string_view t, int64_t count, bool *ok) {
    int64_t idx = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), idx);
    *ok = ec == std::errc() && end == t.data() + t.size();
    if (!*ok || idx == 0) return -1;
    const int64_t resolved = idx > 0 ? idx - 1 : count + idx;
    return resolved >= 0 && resolved < count ? resolved : -1;
}

// Checks that tokens [first, first + n) of a `vt`/`vn` line are finite numbers.
template <typename Fail>
void check_numbers(const std::vector<std::string_view> &tok, size_t first, size_t n,
                   const Fail &fail) {
    for (size_t i = first; i < first + n; ++i) {
        double x = 0;
        const auto [end, ec] =
            std::from_chars(tok[i].data(), tok[i].data() + tok[i].size(), x);
        if (ec != std::errc() || end != tok[i].data() + tok[i].size())
            fail("malformed number '" + std::string(tok[i]) + "'");
        if (!std::isfinite(x)) fail("non-finite number '" + std::string(tok[i]) + "'");
    }
}

// Validates `v`, `vt`, `vn` and `f` lines (every corner's vertex, texture and normal
// index in range: tinyobjloader does not check them); returns the number of corners of
// every face in file order.
std::vector<uint32_t> validate_obj(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, 0, "", "cannot open file");
    std::vector<uint32_t> face_corners;
    std::string line;
    size_t line_no = 0;
    int64_t num_v = 0, num_vt = 0, num_vn = 0;
    std::vector<std::string_view> tok;
    for (;;) {
        const LineRead r = read_line(in, line);
        if (r == LineRead::end_of_file) break;
        ++line_no;
        if (r == LineRead::too_long)
            throw InputError(
                path, line_no, "",
                "line longer than " + std::to_string(max_line_bytes) + " bytes");
        if (auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
        split_whitespace(line, tok);
        if (tok.empty()) continue;
        auto fail = [&](const std::string &msg) {
            throw InputError(path, line_no, "", msg);
        };
        if (tok[0] == "v") {
            if (tok.size() < 4) fail("malformed vertex: expected 3 coordinates");
            for (size_t i = 1; i < 4; ++i) {
                double x = 0;
                const auto [end, ec] =
                    std::from_chars(tok[i].data(), tok[i].data() + tok[i].size(), x);
                if (ec != std::errc() || end != tok[i].data() + tok[i].size())
                    fail("malformed coordinate '" + std::string(tok[i]) + "'");
                if (!std::isfinite(x))
                    fail("non-finite coordinate '" + std::string(tok[i]) + "'");
            }
            ++num_v;
        } else if (tok[0] == "vt") {
            if (tok.size() < 2) fail("malformed texture coordinate: expected u [v [w]]");
            check_numbers(tok, 1, std::min<size_t>(tok.size() - 1, 3), fail);
            ++num_vt;
        } else if (tok[0] == "vn") {
            if (tok.size() < 4) fail("malformed normal: expected 3 coordinates");
            check_numbers(tok, 1, 3, fail);
            ++num_vn;
        } else if (tok[0] == "f") {
            if (tok.size() < 4)
                fail("face has " + std::to_string(tok.size() - 1) +
                     " corners (a face needs at least 3)");
            for (size_t i = 1; i < tok.size(); ++i) {
                // Corner forms: v, v/vt, v//vn, v/vt/vn.
                const std::string_view t = tok[i];
                std::string_view part[3];
                size_t parts = 0;
                for (size_t start = 0;;) {
                    const size_t slash = t.find('/', start);
                    if (parts == 3)
                        fail("malformed face corner '" + std::string(t) + "'");
                    part[parts++] = t.substr(start, slash - start);
                    if (slash == std::string_view::npos) break;
                    start = slash + 1;
                }
                const struct {
                    int64_t count;
                    const char *what, *plural;
                } kinds[3] = {{num_v, "vertex", "vertices"},
                              {num_vt, "texture", "texture coordinates"},
                              {num_vn, "normal", "normals"}};
                for (size_t k = 0; k < parts; ++k) {
                    if (k > 0 && part[k].empty()) continue;  // v//vn, or a trailing '/'
                    bool ok = false;
                    if (resolve_obj_index(part[k], kinds[k].count, &ok) >= 0) continue;
                    if (!ok) fail("malformed face corner '" + std::string(t) + "'");
                    fail(std::string(kinds[k].what) + " index " + std::string(part[k]) +
                         " out of range (" + std::to_string(kinds[k].count) + " " +
                         kinds[k].plural + " defined so far)");
                }
            }
            face_corners.push_back(static_cast<uint32_t>(tok.size() - 1));
        }
    }
    if (num_v == 0 || face_corners.empty())
        throw InputError(path, 0, "", "empty mesh: no vertices or no faces");
    return face_corners;
}

}  // namespace

TriangleMesh read_obj(const std::string &path, MeshReadStats *stats) {
    const std::vector<uint32_t> face_corners = validate_obj(path);

    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    config.mtl_search_path = "";  // materials come from the scene, not from .mtl files
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path, config))
        throw InputError(path, 0, "", "OBJ parse error: " + reader.Error());

    const tinyobj::attrib_t &attrib = reader.GetAttrib();
    TriangleMesh mesh;
    const size_t nv = attrib.vertices.size() / 3;
    mesh.positions.resize(nv);
    for (size_t v = 0; v < nv; ++v)
        mesh.positions[v] = {attrib.vertices[3 * v], attrib.vertices[3 * v + 1],
                             attrib.vertices[3 * v + 2]};

    // Per-corner attributes are kept only when every corner has them.
    bool all_normals = !attrib.normals.empty(), all_uvs = !attrib.texcoords.empty();
    for (const auto &shape : reader.GetShapes())
        for (const auto &idx : shape.mesh.indices) {
            all_normals &= idx.normal_index >= 0;
            all_uvs &= idx.texcoord_index >= 0;
        }
    for (const auto &shape : reader.GetShapes()) {
        const auto &m = shape.mesh;
        if (m.indices.size() != 3 * m.num_face_vertices.size())
            throw InputError(path, 0, "",
                             "OBJ triangulation left a face that is not a triangle");
        for (size_t f = 0; f < m.num_face_vertices.size(); ++f) {
            std::array<VertId, 3> tri{};
            for (int c = 0; c < 3; ++c) {
                const tinyobj::index_t idx = m.indices[3 * f + c];
                // validate_obj() checked every index; this guards against tinyobjloader
                // resolving one differently from us.
                if (idx.vertex_index < 0 || size_t(idx.vertex_index) >= nv ||
                    (all_normals &&
                     size_t(idx.normal_index) >= attrib.normals.size() / 3) ||
                    (all_uvs &&
                     size_t(idx.texcoord_index) >= attrib.texcoords.size() / 2))
                    throw InputError(path, 0, "", "face index out of range");
                tri[c] = static_cast<VertId>(idx.vertex_index);
                if (all_normals)
                    mesh.corner_normals.push_back(
                        {attrib.normals[3 * idx.normal_index],
                         attrib.normals[3 * idx.normal_index + 1],
                         attrib.normals[3 * idx.normal_index + 2]});
                if (all_uvs)
                    mesh.corner_uvs.push_back(
                        {attrib.texcoords[2 * idx.texcoord_index],
                         attrib.texcoords[2 * idx.texcoord_index + 1]});
            }
            mesh.triangles.push_back(tri);
        }
    }

    // Point each triangle back at its source face: an n-gon fans into n - 2 triangles.
    size_t expected = 0;
    for (uint32_t n : face_corners) expected += n - 2;
    if (expected == mesh.triangles.size()) {
        for (uint32_t f = 0; f < face_corners.size(); ++f)
            for (uint32_t k = 0; k + 2 < face_corners[f]; ++k)
                mesh.source_face.push_back(f);
    } else {  // the triangulator dropped degenerate pieces: fall back to triangle order
        for (uint32_t t = 0; t < mesh.triangles.size(); ++t)
            mesh.source_face.push_back(t);
    }
    if (stats)
        for (uint32_t n : face_corners) stats->polygons_triangulated += n > 3;
    return mesh;
}

}  // namespace pelage::sim
