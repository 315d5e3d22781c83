// OBJ reader: tinyobjloader does the parsing, polygon triangulation and the .mtl files.
// tinyobjloader is lenient (a malformed number reads as 0, a bad index may be skipped),
// so a short validating pass first checks the lines that define geometry and reports the
// first bad one with its line number: we never render a mesh the file did not describe.
// The same pass records which `o` and `g` names each face is under, for selecting one.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string_view>
#include <vector>

#ifndef TINYOBJLOADER_USE_DOUBLE
#define TINYOBJLOADER_USE_DOUBLE  // must match the linked libtinyobjloader_double
#endif
#include <tiny_obj_loader.h>

#include "sim/core/input_error.h"
#include "sim/core/text_lines.h"
#include "sim/mesh/mesh_io.h"
#include "sim/mesh/mesh_objects.h"

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

// Checks every corner of an `f` line: its form, and that its vertex, texture and normal
// indices name elements defined so far.
template <typename Fail>
void check_face_corners(const std::vector<std::string_view> &tok, int64_t num_v,
                        int64_t num_vt, int64_t num_vn, const Fail &fail) {
    for (size_t i = 1; i < tok.size(); ++i) {
        // Corner forms: v, v/vt, v//vn, v/vt/vn.
        const std::string_view t = tok[i];
        std::string_view part[3];
        size_t parts = 0;
        for (size_t start = 0;;) {
            const size_t slash = t.find('/', start);
            if (parts == 3) fail("malformed face corner '" + std::string(t) + "'");
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
}

// What the validating pass learns of the faces, in file order.
struct ObjScan {
    std::vector<uint32_t> face_corners;
    // Each face's names: the `o` name it is under and its `g` names, as an index into
    // `labels` (faces under the same names share one).
    std::vector<uint32_t> face_label;
    std::vector<std::vector<std::string>> labels{{}};
    // Faces between two `o`/`g` lines, which is what tinyobjloader makes a shape of.
    std::vector<uint32_t> segment_faces{0};
    std::vector<std::string> mtllibs;  // as written after `mtllib`
};

// Validates `v`, `vt`, `vn` and `f` lines (every corner's vertex, texture and normal
// index in range: tinyobjloader does not check them) and records the names of the faces.
ObjScan validate_obj(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, 0, "", "cannot open file");
    ObjScan scan;
    std::vector<uint32_t> &face_corners = scan.face_corners;
    std::string object_name;               // the current `o`
    std::vector<std::string> group_names;  // the current `g`
    std::map<std::vector<std::string>, uint32_t> label_index{{{}, 0}};
    uint32_t label = 0;
    auto names_changed = [&] {
        std::vector<std::string> names = group_names;
        if (!object_name.empty()) names.insert(names.begin(), object_name);
        const auto [it, added] =
            label_index.try_emplace(names, static_cast<uint32_t>(scan.labels.size()));
        if (added) scan.labels.push_back(names);
        label = it->second;
        if (scan.segment_faces.back() > 0) scan.segment_faces.push_back(0);
    };
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
            check_face_corners(tok, num_v, num_vt, num_vn, fail);
            face_corners.push_back(static_cast<uint32_t>(tok.size() - 1));
            scan.face_label.push_back(label);
            ++scan.segment_faces.back();
        } else if (tok[0] == "o") {
            // The rest of the line, its words joined by one space.
            object_name.clear();
            for (size_t i = 1; i < tok.size(); ++i)
                object_name += (i > 1 ? " " : "") + std::string(tok[i]);
            names_changed();
        } else if (tok[0] == "g") {
            group_names.assign(tok.begin() + 1, tok.end());
            names_changed();
        } else if (tok[0] == "mtllib") {
            scan.mtllibs.insert(scan.mtllibs.end(), tok.begin() + 1, tok.end());
        }
    }
    if (num_v == 0 || face_corners.empty())
        throw InputError(path, 0, "", "empty mesh: no vertices or no faces");
    return scan;
}

// The file's materials, map_Kd made absolute against the folder of the .mtl it is in
// (tinyobjloader does not say which: the first .mtl folder that holds the texture).
std::vector<MeshMaterial> obj_materials(const std::string &path, const ObjScan &scan,
                                        const std::vector<tinyobj::material_t> &mats) {
    namespace fs = std::filesystem;
    const fs::path obj_dir = fs::absolute(fs::path(path)).parent_path();
    std::vector<fs::path> mtl_dirs;
    for (const std::string &m : scan.mtllibs)
        mtl_dirs.push_back((obj_dir / fs::path(m)).parent_path().lexically_normal());
    if (mtl_dirs.empty()) mtl_dirs.push_back(obj_dir);
    std::vector<MeshMaterial> out;
    for (const tinyobj::material_t &m : mats) {
        MeshMaterial mm;
        mm.name = m.name;
        mm.diffuse = {m.diffuse[0], m.diffuse[1], m.diffuse[2]};
        if (!m.diffuse_texname.empty()) {
            const fs::path t(m.diffuse_texname);
            fs::path chosen = t.is_absolute() ? t : mtl_dirs[0] / t;
            if (!t.is_absolute())
                for (const fs::path &d : mtl_dirs) {
                    std::error_code ec;
                    if (fs::is_regular_file(d / t, ec)) {
                        chosen = d / t;
                        break;
                    }
                }
            mm.diffuse_texture = chosen.lexically_normal().string();
        }
        out.push_back(std::move(mm));
    }
    return out;
}

// The names there are, in file order, and which labels the selection keeps (every one
// when no object is named).
struct ObjSelection {
    std::vector<std::string> names;
    std::vector<char> label_kept;
};

ObjSelection select_object(const std::string &path, const ObjScan &scan,
                           const std::string &object) {
    std::vector<std::string> all_names;
    for (uint32_t l : scan.face_label)
        all_names.insert(all_names.end(), scan.labels[l].begin(), scan.labels[l].end());
    ObjSelection selection;
    selection.names = unique_names(all_names);
    std::vector<char> &label_kept = selection.label_kept;
    label_kept.assign(scan.labels.size(), object.empty());
    if (!object.empty()) {
        bool found = false;
        for (size_t l = 0; l < scan.labels.size(); ++l)
            for (const std::string &n : scan.labels[l])
                if (n == object) label_kept[l] = 1, found = true;
        if (!found) fail_unknown_object(path, object, selection.names);
    }
    return selection;
}

// Each triangle's source face, in tinyobjloader's shape order: an n-gon fans into n - 2
// triangles, unless the triangulator dropped degenerate pieces; then shapes stand for
// segments.
std::vector<uint32_t> triangle_source_faces(const std::string &path,
                                            const std::string &object,
                                            const ObjScan &scan,
                                            const std::vector<tinyobj::shape_t> &shapes) {
    const std::vector<uint32_t> &face_corners = scan.face_corners;
    size_t num_tris = 0;
    for (const auto &shape : shapes) num_tris += shape.mesh.num_face_vertices.size();
    std::vector<uint32_t> tri_face;
    size_t expected = 0;
    for (uint32_t n : face_corners) expected += n - 2;
    if (expected == num_tris) {
        for (uint32_t f = 0; f < face_corners.size(); ++f)
            for (uint32_t k = 0; k + 2 < face_corners[f]; ++k) tri_face.push_back(f);
        return tri_face;
    }
    std::vector<uint32_t> segment_first;  // first face of each segment with faces
    uint32_t first = 0;
    for (uint32_t n : scan.segment_faces) {
        if (n > 0) segment_first.push_back(first);
        first += n;
    }
    std::vector<const tinyobj::shape_t *> with_faces;
    for (const auto &shape : shapes)
        if (!shape.mesh.num_face_vertices.empty()) with_faces.push_back(&shape);
    if (with_faces.size() != segment_first.size()) {
        if (!object.empty())
            throw InputError(path, 0, "",
                             "cannot tell which triangles belong to object \"" + object +
                                 "\": triangulating a degenerate polygon dropped it");
        for (uint32_t t = 0; t < num_tris; ++t) tri_face.push_back(t);
    } else {
        // Only the first face of each segment is known: enough for the names.
        for (size_t s = 0; s < with_faces.size(); ++s)
            tri_face.insert(tri_face.end(), with_faces[s]->mesh.num_face_vertices.size(),
                            segment_first[s]);
    }
    return tri_face;
}

// tinyobjloader's triangles, in shape order, and what the selection makes of them.
struct ObjTriangles {
    const std::string &path;
    const std::string &object;
    const ObjScan &scan;
    const tinyobj::attrib_t &attrib;
    const std::vector<tinyobj::shape_t> &shapes;
    const std::vector<char> &label_kept;
    const std::vector<uint32_t> &tri_face;  // per triangle
    size_t nv = 0;                          // vertices read
    // Per-corner attributes are kept only when every kept corner has them.
    bool all_normals = false, all_uvs = false;

    bool kept(size_t t) const {
        const uint32_t f = tri_face[t];
        return f < scan.face_label.size() ? bool(label_kept[scan.face_label[f]])
                                          : object.empty();
    }

    void find_corner_attributes() {
        all_normals = !attrib.normals.empty();
        all_uvs = !attrib.texcoords.empty();
        size_t t = 0;
        for (const auto &shape : shapes)
            for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f, ++t) {
                if (!kept(t)) continue;
                for (int c = 0; c < 3; ++c) {
                    const tinyobj::index_t idx = shape.mesh.indices[3 * f + c];
                    all_normals &= idx.normal_index >= 0;
                    all_uvs &= idx.texcoord_index >= 0;
                }
            }
    }

    // The kept triangles into mesh, each with its source face and material (an index
    // below num_materials, or invalid_id), marking the labels read. Returns whether any
    // triangle has a material.
    bool append_kept(size_t num_materials, TriangleMesh &mesh,
                     std::vector<char> &label_read) const {
        bool any_material = false;
        size_t t = 0;
        for (const auto &shape : shapes) {
            const auto &m = shape.mesh;
            if (m.indices.size() != 3 * m.num_face_vertices.size())
                throw InputError(path, 0, "",
                                 "OBJ triangulation left a face that is not a triangle");
            for (size_t f = 0; f < m.num_face_vertices.size(); ++f, ++t) {
                if (!kept(t)) continue;
                std::array<VertId, 3> tri{};
                for (int c = 0; c < 3; ++c)
                    tri[c] = append_corner(m.indices[3 * f + c], mesh);
                mesh.triangles.push_back(tri);
                mesh.source_face.push_back(tri_face[t]);
                const int mat = f < m.material_ids.size() ? m.material_ids[f] : -1;
                const bool has_mat = mat >= 0 && size_t(mat) < num_materials;
                mesh.triangle_material.push_back(has_mat ? uint32_t(mat) : invalid_id);
                any_material |= has_mat;
                if (tri_face[t] < scan.face_label.size())
                    label_read[scan.face_label[tri_face[t]]] = 1;
            }
        }
        return any_material;
    }

    // A corner's normal and uv into mesh, where every corner has them; returns its
    // vertex.
    VertId append_corner(const tinyobj::index_t idx, TriangleMesh &mesh) const {
        // validate_obj() checked every index; this guards against tinyobjloader
        // resolving one differently from us.
        if (idx.vertex_index < 0 || size_t(idx.vertex_index) >= nv ||
            (all_normals && size_t(idx.normal_index) >= attrib.normals.size() / 3) ||
            (all_uvs && size_t(idx.texcoord_index) >= attrib.texcoords.size() / 2))
            throw InputError(path, 0, "", "face index out of range");
        if (all_normals)
            mesh.corner_normals.push_back({attrib.normals[3 * idx.normal_index],
                                           attrib.normals[3 * idx.normal_index + 1],
                                           attrib.normals[3 * idx.normal_index + 2]});
        if (all_uvs)
            mesh.corner_uvs.push_back({attrib.texcoords[2 * idx.texcoord_index],
                                       attrib.texcoords[2 * idx.texcoord_index + 1]});
        return static_cast<VertId>(idx.vertex_index);
    }
};

}  // namespace

TriangleMesh read_obj(const std::string &path, MeshReadStats *stats,
                      const std::string &object) {
    const ObjScan scan = validate_obj(path);
    const ObjSelection selection = select_object(path, scan, object);

    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    config.mtl_search_path = "";  // the .obj's folder
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path, config))
        throw InputError(path, 0, "", "OBJ parse error: " + reader.Error());

    const tinyobj::attrib_t &attrib = reader.GetAttrib();
    const auto &shapes = reader.GetShapes();
    TriangleMesh mesh;
    const size_t nv = attrib.vertices.size() / 3;
    mesh.positions.resize(nv);
    for (size_t v = 0; v < nv; ++v)
        mesh.positions[v] = {attrib.vertices[3 * v], attrib.vertices[3 * v + 1],
                             attrib.vertices[3 * v + 2]};

    const std::vector<uint32_t> tri_face =
        triangle_source_faces(path, object, scan, shapes);
    ObjTriangles triangles{path,     object, scan, attrib, shapes, selection.label_kept,
                           tri_face, nv};
    triangles.find_corner_attributes();
    const std::vector<MeshMaterial> materials =
        obj_materials(path, scan, reader.GetMaterials());
    std::vector<char> label_read(scan.labels.size(), 0);
    if (triangles.append_kept(materials.size(), mesh, label_read)) {
        mesh.materials = materials;
    } else {
        mesh.triangle_material.clear();
    }
    if (mesh.triangles.empty())
        throw InputError(path, 0, "",
                         object.empty() ? std::string("empty mesh: no triangles")
                                        : "object \"" + object + "\" holds no triangles");
    if (stats) {
        const std::vector<uint32_t> &face_corners = scan.face_corners;
        for (uint32_t f = 0; f < face_corners.size(); ++f)
            stats->polygons_triangulated +=
                face_corners[f] > 3 && selection.label_kept[scan.face_label[f]];
        stats->object_names = selection.names;
        stats->pieces_read = size_t(std::count(label_read.begin(), label_read.end(), 1));
    }
    return mesh;
}

}  // namespace pelage::sim
