#include "renderer/export/glb_writer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <unordered_map>

#include "sim/core/atomic_file.h"

namespace pelage::renderer {
namespace {

// glTF's numbers (specification 5.1.1, accessor.componentType; 5.11, bufferView.target).
constexpr int gl_float = 5126, gl_unsigned_int = 5125;
constexpr int gl_array_buffer = 34962, gl_element_array_buffer = 34963;
constexpr int gl_linear = 9729, gl_linear_mipmap_linear = 9987, gl_clamp_to_edge = 33071;

struct CornerKey {
    uint32_t vertex;
    float n[3], uv[2];
    bool operator==(const CornerKey &o) const {
        return vertex == o.vertex && std::memcmp(n, o.n, sizeof n) == 0 &&
               std::memcmp(uv, o.uv, sizeof uv) == 0;
    }
};
struct CornerHash {
    size_t operator()(const CornerKey &k) const {
        uint32_t b[5];
        std::memcpy(b, k.n, 12);
        std::memcpy(b + 3, k.uv, 8);
        size_t h = k.vertex * 0x9E3779B97F4A7C15ull;
        for (uint32_t x : b) h = (h ^ x) * 0x100000001B3ull;
        return h;
    }
};

void pad_to_4(std::string &s, char with) {
    while (s.size() % 4) s += with;
}

void put_u32(std::string &s, uint32_t v) {
    char b[4];
    std::memcpy(b, &v, 4);  // GLB is little-endian, as is every machine pelage runs on
    s.append(b, 4);
}

}  // namespace

GlbMesh glb_mesh(const std::string &name, const std::vector<double> &positions,
                 const std::vector<uint32_t> &triangles,
                 const std::vector<float> &corner_normals,
                 const std::vector<float> &corner_uvs) {
    GlbMesh m;
    m.name = name;
    std::unordered_map<CornerKey, uint32_t, CornerHash> index;
    const size_t corners = triangles.size();
    // Without normals in the mesh: area-weighted vertex normals (the sum of the faces'
    // cross products), so a viewer shades the skin smooth rather than faceted.
    std::vector<double> vertex_normals;
    if (corner_normals.empty()) {
        vertex_normals.assign(positions.size(), 0.0);
        for (size_t t = 0; 3 * t + 2 < corners; ++t) {
            const double *A = &positions[3 * size_t(triangles[3 * t])];
            const double *B = &positions[3 * size_t(triangles[3 * t + 1])];
            const double *C = &positions[3 * size_t(triangles[3 * t + 2])];
            const double u[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]};
            const double v[3] = {C[0] - A[0], C[1] - A[1], C[2] - A[2]};
            const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                                 u[0] * v[1] - u[1] * v[0]};
            for (int c = 0; c < 3; ++c)
                for (int a = 0; a < 3; ++a)
                    vertex_normals[3 * size_t(triangles[3 * t + size_t(c)]) +
                                   size_t(a)] += n[a];
        }
    }
    for (size_t c = 0; c < corners; ++c) {
        CornerKey k{};
        k.vertex = triangles[c];
        const double *P = &positions[3 * size_t(k.vertex)];
        if (!corner_normals.empty()) {
            std::copy_n(&corner_normals[3 * c], 3, k.n);
        } else {
            const double *n = &vertex_normals[3 * size_t(k.vertex)];
            for (int a = 0; a < 3; ++a) k.n[a] = float(n[a]);
        }
        const float l = std::sqrt(k.n[0] * k.n[0] + k.n[1] * k.n[1] + k.n[2] * k.n[2]);
        if (l > 0) {
            for (float &x : k.n) x /= l;
        } else {
            k.n[0] = 0, k.n[1] = 0, k.n[2] = 1;  // degenerate faces only: any unit normal
        }
        k.uv[0] = corner_uvs[2 * c];
        k.uv[1] = 1 - corner_uvs[2 * c + 1];  // OBJ's v up to glTF's v down
        const auto [it, added] = index.emplace(k, uint32_t(m.positions.size() / 3));
        if (added) {
            for (int a = 0; a < 3; ++a) m.positions.push_back(float(P[a]));
            m.normals.insert(m.normals.end(), k.n, k.n + 3);
            m.uvs.insert(m.uvs.end(), k.uv, k.uv + 2);
        }
        m.indices.push_back(it->second);
    }
    return m;
}

void write_glb(const std::string &path, const GlbMesh &mesh, const std::string &png,
               const std::string &generator) {
    using nlohmann::json;
    const size_t nv = mesh.positions.size() / 3;
    std::string bin;
    json views = json::array(), accessors = json::array();
    auto add_view = [&](const void *data, size_t bytes, int target) {
        const size_t offset = bin.size();
        bin.append(static_cast<const char *>(data), bytes);
        pad_to_4(bin, '\0');
        json v = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}};
        if (target) v["target"] = target;
        views.push_back(v);
        return views.size() - 1;
    };
    auto add_accessor = [&](size_t view, int type, size_t count, const char *shape) {
        accessors.push_back({{"bufferView", view},
                             {"componentType", type},
                             {"count", count},
                             {"type", shape}});
        return accessors.size() - 1;
    };
    // POSITION needs its bounds (specification 5.1.1, accessor.min/max).
    float lo[3] = {INFINITY, INFINITY, INFINITY},
          hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t v = 0; v < nv; ++v)
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], mesh.positions[3 * v + size_t(a)]);
            hi[a] = std::max(hi[a], mesh.positions[3 * v + size_t(a)]);
        }
    const size_t pos = add_accessor(
        add_view(mesh.positions.data(), 4 * mesh.positions.size(), gl_array_buffer),
        gl_float, nv, "VEC3");
    accessors[pos]["min"] = {lo[0], lo[1], lo[2]};
    accessors[pos]["max"] = {hi[0], hi[1], hi[2]};
    json attributes = {{"POSITION", pos}};
    if (!mesh.normals.empty())
        attributes["NORMAL"] = add_accessor(
            add_view(mesh.normals.data(), 4 * mesh.normals.size(), gl_array_buffer),
            gl_float, nv, "VEC3");
    attributes["TEXCOORD_0"] =
        add_accessor(add_view(mesh.uvs.data(), 4 * mesh.uvs.size(), gl_array_buffer),
                     gl_float, nv, "VEC2");
    const size_t indices = add_accessor(
        add_view(mesh.indices.data(), 4 * mesh.indices.size(), gl_element_array_buffer),
        gl_unsigned_int, mesh.indices.size(), "SCALAR");
    const size_t image_view = add_view(png.data(), png.size(), 0);

    const json doc = {
        {"asset", {{"version", "2.0"}, {"generator", generator}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"mesh", 0}, {"name", mesh.name}}}},
        {"meshes",
         {{{"name", mesh.name},
           {"primitives",
            {{{"attributes", attributes}, {"indices", indices}, {"material", 0}}}}}}},
        // The skin's colour is the pattern's albedo; a dielectric, moderately rough.
        {"materials",
         {{{"name", "pattern"},
           {"pbrMetallicRoughness",
            {{"baseColorTexture", {{"index", 0}}},
             {"metallicFactor", 0.0},
             {"roughnessFactor", 0.6}}}}}},
        {"textures", {{{"sampler", 0}, {"source", 0}}}},
        {"images", {{{"bufferView", image_view}, {"mimeType", "image/png"}}}},
        {"samplers",
         {{{"magFilter", gl_linear},
           {"minFilter", gl_linear_mipmap_linear},
           {"wrapS", gl_clamp_to_edge},
           {"wrapT", gl_clamp_to_edge}}}},
        {"buffers", {{{"byteLength", bin.size()}}}},
        {"bufferViews", views},
        {"accessors", accessors},
    };
    std::string text = doc.dump();
    pad_to_4(text, ' ');
    std::string glb;
    put_u32(glb, 0x46546C67);  // "glTF"
    put_u32(glb, 2);
    put_u32(glb, uint32_t(12 + 8 + text.size() + 8 + bin.size()));
    put_u32(glb, uint32_t(text.size()));
    put_u32(glb, 0x4E4F534A);  // "JSON"
    glb += text;
    put_u32(glb, uint32_t(bin.size()));
    put_u32(glb, 0x004E4942);  // "BIN\0"
    glb += bin;
    write_file_atomically(path, [&](std::ostream &out) {
        out.write(glb.data(), std::streamsize(glb.size()));
    });
}

}  // namespace pelage::renderer
