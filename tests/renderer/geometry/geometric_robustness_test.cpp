// Geometric robustness: meshes with needle and sliver triangles,
// boundaries and holes, disconnected components, and scales from 1e-4 to 1e4 units go
// through the whole pipeline (pelage sim, the clonal_mosaic plugin, a render). Cells stay
// on the surface (valid barycentrics in their own triangle), the shader finds a cell at
// every point of every triangle, and no NaN or Inf reaches the film.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "renderer/core/install_layout.h"
#include "renderer/plugins/plugin_loader.h"
#include "sim/cells_io/cells_file.h"
#include "sim/mesh/mesh_load.h"
#include "sim/mesh/procedural_mesh.h"
#include "tests/renderer/render_helpers.h"
#include "tests/shader/plugin_mesh_view.h"
#include "tests/test_paths.h"

namespace pelage::test {
namespace {

using sim::TriangleMesh;
using sim::Vec3d;

// --- Test meshes (written as OFF, so they go through the same reader as users' files)
// ---

void append(TriangleMesh &m, const TriangleMesh &part, Vec3d offset) {
    const auto base = uint32_t(m.positions.size());
    for (const Vec3d &p : part.positions) m.positions.push_back(p + offset);
    for (const auto &t : part.triangles)
        m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
}

// A 1 × 1 grid whose rows and columns include widths of 1e-4: needles with an aspect
// ratio of 10^4, and slivers where a needle row crosses a needle column.
TriangleMesh needles() {
    const std::vector<double> xs{0, 0.3, 0.3001, 0.7, 1}, zs{0, 0.2, 0.5, 0.5001, 1};
    TriangleMesh m;
    for (double z : zs)
        for (double x : xs) m.positions.push_back({x, 0.1 * std::sin(3 * x + 2 * z), z});
    const auto nx = uint32_t(xs.size());
    for (uint32_t j = 0; j + 1 < zs.size(); ++j)
        for (uint32_t i = 0; i + 1 < nx; ++i) {
            const uint32_t a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
            m.triangles.push_back({a, c, b});
            m.triangles.push_back({b, c, d});
        }
    return m;
}

// A 12 × 12 plane with a 4 × 4 hole in the middle and two single-quad holes.
TriangleMesh plane_with_holes() {
    const TriangleMesh full = sim::make_plane(12, 12, 1.0, 1.0);
    TriangleMesh m;
    m.positions = full.positions;
    for (size_t t = 0; t < full.triangles.size(); ++t) {
        const size_t quad = t / 2, i = quad % 12, j = quad / 12;
        const bool hole = (i >= 4 && i < 8 && j >= 4 && j < 8) || (i == 1 && j == 1) ||
                          (i == 10 && j == 2);
        if (!hole) m.triangles.push_back(full.triangles[t]);
    }
    return m;
}

// Two closed spheres and an open plane, none touching.
TriangleMesh disconnected() {
    TriangleMesh m;
    append(m, sim::make_icosphere(2, 0.4), {-0.6, 0, 0});
    append(m, sim::make_icosphere(1, 0.25), {0.6, 0, 0});
    append(m, sim::make_plane(4, 4, 1.6, 0.6), {0, -0.5, 0});
    return m;
}

TriangleMesh scaled(TriangleMesh m, double s) {
    for (Vec3d &p : m.positions) p = p * s;
    return m;
}

std::string write_off(const TempDir &tmp, const std::string &name,
                      const TriangleMesh &m) {
    std::ostringstream s;
    s.precision(17);
    s << "OFF\n" << m.positions.size() << ' ' << m.triangles.size() << " 0\n";
    for (const Vec3d &p : m.positions) s << p.x << ' ' << p.y << ' ' << p.z << '\n';
    for (const auto &t : m.triangles)
        s << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
    return tmp.write(name, s.str());
}

std::string plugin_file() {
    return renderer::package_lib_dir() + "/shaders/clonal_mosaic.so";
}

struct Case {
    std::string name;
    TriangleMesh mesh;
};

void check_case(const Case &c) {
    SCOPED_TRACE(c.name);
    TempDir tmp;
    const std::string mesh_path = write_off(tmp, c.name + ".off", c.mesh);
    const std::string cells_path = simulate_two_type_cells(tmp, mesh_path, 150);
    const TriangleMesh mesh = sim::load_mesh(mesh_path);  // as the renderer sees it

    // --- Cells stay on the surface: inside their own triangle, finite ---
    const sim::CellsData data = sim::read_cells_file(cells_path);
    ASSERT_EQ(data.num_triangles(), mesh.num_triangles());
    ASSERT_GT(data.num_cells(), 0u);
    std::set<uint32_t> ids;
    for (sim::TriId t = 0; t < data.num_triangles(); ++t)
        for (uint32_t k = data.cell_row[t]; k < data.cell_row[t + 1]; ++k) {
            ASSERT_TRUE(std::isfinite(data.x[k]) && std::isfinite(data.z[k]));
            const Vec3d b = sim::barycentric_in(data.frames[t], {data.x[k], data.z[k]});
            // Barycentrics are scale-free; 1e-6 allows the rounding of the 2D frame of a
            // needle whose height is 1e-4 of its length.
            for (double bi : {b.x, b.y, b.z})
                ASSERT_GE(bi, -1e-6) << "cell " << k << " off triangle " << t;
            ids.insert(data.id[k]);
        }

    // --- The shader finds a cell at the corners, edges and centre of every triangle ---
    const renderer::LoadedPlugin plugin = renderer::open_plugin(plugin_file());
    const renderer::PluginParams params = renderer::validate_plugin_params(
        *plugin.desc, nlohmann::json{{"antialias", 0}}, "test.json", "params");
    const test::PluginMeshView view(mesh, mesh_path, cells_path.c_str());
    PelageParamSet ps{};
    ps.count = uint32_t(params.values.size());
    ps.values = params.values.data();
    ps.mesh = view.view;
    ps.warn = test::PluginMeshView::warn;
    PelageError err{};
    void *self = plugin.desc->create(&ps, &err);
    ASSERT_NE(self, nullptr) << err.message;
    const float points[][2] = {
        {0, 0}, {1, 0}, {0, 1}, {0.5f, 0}, {0, 0.5f}, {0.5f, 0.5f}, {1 / 3.0f, 1 / 3.0f}};
    for (uint32_t prim = 0; prim < mesh.num_triangles(); ++prim)
        for (const auto &p : points) {
            PelageHit hit{};
            hit.primitive_id = prim;
            hit.b1 = p[0];
            hit.b2 = p[1];
            PelageShade out{};
            out.roughness = -1;
            plugin.desc->shade(self, &hit, &out);
            ASSERT_EQ(out.aov_written, 1u) << "no cell at triangle " << prim;
            ASSERT_TRUE(ids.count(uint32_t(out.aov[0]))) << "triangle " << prim;
            for (float a : out.albedo) ASSERT_TRUE(std::isfinite(a));
            ASSERT_TRUE(std::isfinite(out.aov[2]));
        }
    plugin.desc->destroy(self);

    // --- A render framing the mesh: every channel of every pixel finite ---
    const sim::Bounds3 bb = mesh.bounds();
    const Vec3d centre = (bb.lo + bb.hi) * 0.5;
    const double r = 0.5 * bb.diagonal();
    std::ostringstream scene;
    scene.precision(17);
    auto vec = [&](Vec3d v) {
        std::ostringstream s;
        s.precision(17);
        s << '[' << v.x << ", " << v.y << ", " << v.z << ']';
        return s.str();
    };
    scene << R"({"camera": {"position": )"
          << vec(centre + Vec3d{0.4 * r, 1.6 * r, 1.8 * r}) << R"(, "look_at": )"
          << vec(centre) << R"(, "fov": 60},
        "film": {"width": 32, "height": 32, "spp": 2},
        "lights": [{"type": "environment", "intensity": 1},
                   {"type": "distant", "direction": [-0.3, -1, -0.2], "intensity": 2}],
        "objects": [{"name": "m", "mesh": ")"
          << mesh_path << R"(", "cells": ")" << cells_path << R"(",
                     "material": {"shader": "clonal_mosaic", "bsdf": "coated"}}]})";
    const RenderedImage img = render_json(scene.str(), tmp);
    size_t hits = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            // Every channel finite; depth is +inf where nothing was hit.
            for (int ch = 0; ch < renderer::Film::num_channels; ++ch)
                ASSERT_TRUE(std::isfinite(img.at(x, y, ch)) ||
                            (ch == 10 && img.at(x, y, 11) < 0 && img.at(x, y, ch) > 0))
                    << "pixel " << x << "," << y << " channel " << ch;
            if (img.at(x, y, 11) >= 0) {  // id.object: the primary ray hit the mesh
                ++hits;
                ASSERT_TRUE(ids.count(uint32_t(img.at(x, y, 13))))
                    << "pixel " << x << "," << y;
            }
        }
    EXPECT_GT(hits, 32u * 32u / 20) << "the camera should see the mesh";
}

TEST(GeometricRobustness, NeedleAndSliverTriangles) {
    check_case({"needles", needles()});
}
TEST(GeometricRobustness, BoundariesAndHoles) {
    check_case({"holes", plane_with_holes()});
}
TEST(GeometricRobustness, DisconnectedComponents) {
    check_case({"disconnected", disconnected()});
}
TEST(GeometricRobustness, TinyScale1em4) {
    check_case({"tiny", scaled(sim::make_icosphere(2), 1e-4)});
}
TEST(GeometricRobustness, HugeScale1e4) {
    check_case({"huge", scaled(sim::make_icosphere(2), 1e4)});
}
TEST(GeometricRobustness, NeedlesAtBothExtremeScales) {
    check_case({"needles_tiny", scaled(needles(), 1e-4)});
    check_case({"needles_huge", scaled(needles(), 1e4)});
}

}  // namespace
}  // namespace pelage::test
