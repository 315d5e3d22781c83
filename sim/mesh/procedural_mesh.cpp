#include "sim/mesh/procedural_mesh.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "sim/core/input_error.h"

namespace pelage::sim {
namespace {

constexpr double pi = std::numbers::pi;

void add_quad(TriangleMesh &m, VertId a, VertId b, VertId c, VertId d) {  // a b c d CCW
    m.triangles.push_back({a, b, c});
    m.triangles.push_back({a, c, d});
}

void finish(TriangleMesh &m) {
    m.source_face.resize(m.triangles.size());
    for (uint32_t t = 0; t < m.source_face.size(); ++t) m.source_face[t] = t;
}

}  // namespace

TriangleMesh make_uv_sphere(int stacks, int slices, double radius) {
    TriangleMesh m;
    m.positions.push_back({0, radius, 0});  // north pole
    for (int i = 1; i < stacks; ++i) {
        const double theta = pi * i / stacks;
        for (int j = 0; j < slices; ++j) {
            const double phi = 2 * pi * j / slices;
            m.positions.push_back({radius * std::sin(theta) * std::cos(phi),
                                   radius * std::cos(theta),
                                   -radius * std::sin(theta) * std::sin(phi)});
        }
    }
    m.positions.push_back({0, -radius, 0});  // south pole
    const VertId south = static_cast<VertId>(m.positions.size() - 1);
    auto ring = [&](int i, int j) {
        return static_cast<VertId>(1 + (i - 1) * slices + (j % slices));
    };
    for (int j = 0; j < slices; ++j)
        m.triangles.push_back({0, ring(1, j), ring(1, j + 1)});
    for (int i = 1; i + 1 < stacks; ++i)
        for (int j = 0; j < slices; ++j)
            add_quad(m, ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j + 1));
    for (int j = 0; j < slices; ++j)
        m.triangles.push_back({south, ring(stacks - 1, j + 1), ring(stacks - 1, j)});
    finish(m);
    return m;
}

TriangleMesh make_icosphere(int level, double radius) {
    TriangleMesh m;
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    const Vec3d v[12] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                         {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                         {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (const Vec3d &p : v) m.positions.push_back(normalize(p) * radius);
    m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                   {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                   {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                   {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int l = 0; l < level; ++l) {
        std::map<std::pair<VertId, VertId>, VertId> mid;
        auto midpoint = [&](VertId a, VertId b) {
            const auto key = std::minmax(a, b);
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            const VertId id = static_cast<VertId>(m.positions.size());
            m.positions.push_back(normalize(m.positions[a] + m.positions[b]) * radius);
            mid.emplace(key, id);
            return id;
        };
        std::vector<std::array<VertId, 3>> next;
        for (const auto &f : m.triangles) {
            const VertId a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]),
                         c = midpoint(f[2], f[0]);
            next.push_back({f[0], a, c});
            next.push_back({f[1], b, a});
            next.push_back({f[2], c, b});
            next.push_back({a, b, c});
        }
        m.triangles = std::move(next);
    }
    finish(m);
    return m;
}

TriangleMesh make_torus(int nu, int nv, double R, double r) {
    TriangleMesh m;
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            const double u = 2 * pi * i / nu, v = 2 * pi * j / nv;
            m.positions.push_back({(R + r * std::cos(v)) * std::cos(u), r * std::sin(v),
                                   -(R + r * std::cos(v)) * std::sin(u)});
        }
    auto id = [&](int i, int j) { return static_cast<VertId>((i % nu) * nv + (j % nv)); };
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j)
            add_quad(m, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
    finish(m);
    return m;
}

TriangleMesh make_plane(int nx, int nz, double sx, double sz) {
    TriangleMesh m;
    for (int i = 0; i <= nz; ++i)
        for (int j = 0; j <= nx; ++j)
            m.positions.push_back(
                {sx * (double(j) / nx - 0.5), 0, sz * (double(i) / nz - 0.5)});
    auto id = [&](int i, int j) { return static_cast<VertId>(i * (nx + 1) + j); };
    // Counter-clockwise seen from +Y: x then -z.
    for (int i = 0; i < nz; ++i)
        for (int j = 0; j < nx; ++j)
            add_quad(m, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
    finish(m);
    return m;
}

TriangleMesh make_cylinder(int around, int along, double radius, double height) {
    TriangleMesh m;
    for (int i = 0; i <= along; ++i)
        for (int j = 0; j < around; ++j) {
            const double phi = 2 * pi * j / around;
            m.positions.push_back({radius * std::cos(phi),
                                   height * (double(i) / along - 0.5),
                                   -radius * std::sin(phi)});
        }
    auto id = [&](int i, int j) {
        return static_cast<VertId>(i * around + (j % around));
    };
    for (int i = 0; i < along; ++i)
        for (int j = 0; j < around; ++j)
            add_quad(m, id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j));
    finish(m);
    return m;
}

TriangleMesh make_procedural(const std::string &spec) {
    // kind:A or kind:AxB, with A and B decimal numbers of at most four digits.
    const auto fail_syntax = [&] {
        throw InputError(spec, 0, "",
                         "malformed procedural mesh (expected sphere:SxS, "
                         "icosphere:L, torus:UxV, plane:NxN or cylinder:AxL)");
    };
    const size_t colon = spec.find(':');
    if (colon == std::string::npos) fail_syntax();
    const std::string kind = spec.substr(0, colon);
    if (kind != "sphere" && kind != "icosphere" && kind != "torus" && kind != "plane" &&
        kind != "cylinder")
        fail_syntax();
    const std::string sizes = spec.substr(colon + 1);
    const size_t x = sizes.find('x');
    auto number = [&](const std::string &digits) {
        if (digits.empty() || digits.size() > 4 ||
            digits.find_first_not_of("0123456789") != std::string::npos)
            fail_syntax();
        return std::stoi(digits);
    };
    const int a = number(sizes.substr(0, x));
    const bool has_b = x != std::string::npos;
    const int b = has_b ? number(sizes.substr(x + 1)) : 0;
    auto need = [&](bool ok, const char *what) {
        if (!ok) throw InputError(spec, 0, "", what);
    };
    if (kind == "icosphere") {
        need(!has_b && a <= 8, "icosphere takes one subdivision level, at most 8");
        return make_icosphere(a);
    }
    need(has_b, "this procedural mesh takes two sizes, e.g. sphere:20x20");
    if (kind == "sphere") {
        need(a >= 2 && b >= 3, "sphere needs at least 2 stacks and 3 slices");
        return make_uv_sphere(a, b);
    }
    if (kind == "torus") {
        need(a >= 3 && b >= 3, "torus needs at least 3x3 segments");
        return make_torus(a, b, 1.0, 0.35);
    }
    if (kind == "plane") {
        need(a >= 1 && b >= 1, "plane needs at least 1x1 quads");
        return make_plane(a, b, 2.0, 2.0 * b / a);
    }
    need(a >= 3 && b >= 1, "cylinder needs at least 3 segments around and 1 along");
    return make_cylinder(a, b, 1.0, 2.0);
}

}  // namespace pelage::sim
