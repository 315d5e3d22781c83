#include "sim/control/surface_control.h"

#include <OpenImageIO/imagebuf.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/control/corner_transfer.h"
#include "sim/core/input_error.h"
#include "sim/crps/body_length.h"
#include "sim/geodesic/geodesic_mesh.h"
#include "sim/geodesic/window_propagation.h"
#include "sim/mesh/closest_point.h"

namespace pelage::sim {
namespace {

// 1 at x <= 0, falling smoothly (smoothstep) to 0 at x >= 1.
double fade(double x) {
    if (x <= 0) return 1;
    if (x >= 1) return 0;
    return 1 - x * x * (3 - 2 * x);
}

// 1 up to `limit`, fading to 0 over `blend` beyond (a hard edge when blend is 0).
double inside(double over, double blend) {
    if (over <= 0) return 1;
    return blend > 0 ? fade(over / blend) : 0;
}

std::vector<double> height_values(const RegionSpec &r, const TriangleMesh &mesh) {
    const Vec3d a{r.axis[0], r.axis[1], r.axis[2]};
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const auto &tri : mesh.triangles)
        for (VertId v : tri) {
            const double h = dot(mesh.positions[v], a);
            lo = std::min(lo, h);
            hi = std::max(hi, h);
        }
    const double extent = std::max(hi - lo, 1e-300);
    std::vector<double> out(3 * mesh.num_triangles());
    for (TriId t = 0; t < mesh.num_triangles(); ++t)
        for (int c = 0; c < 3; ++c) {
            const double h = (dot(mesh.vertex(t, c), a) - lo) / extent;
            double v = 1;
            if (r.has_below) v *= inside(h - r.below, r.blend);
            if (r.has_above) v *= inside(r.above - h, r.blend);
            out[3 * size_t(t) + c] = v;
        }
    return out;
}

// Exact polyhedral geodesic distance (Chen & Han window propagation) from each point,
// snapped to its closest surface point, to every corner within reach.
std::vector<double> near_values(const RegionSpec &r, const TriangleMesh &mesh,
                                const Crps &crps) {
    const double L = body_axis(crps).length;
    const double reach = (r.within + r.blend) * L;
    const Bounds3 box = mesh.bounds();
    const GeodesicMesh gmesh(crps);
    WindowPropagation propagation(gmesh);
    std::vector<double> distance(3 * mesh.num_triangles(),
                                 std::numeric_limits<double>::infinity());
    std::vector<GeodesicWindow> windows;
    for (const auto &q : r.points) {
        Vec3d p{q[0], q[1], q[2]};
        if (r.box_space)
            p = {box.lo.x + q[0] * (box.hi.x - box.lo.x),
                 box.lo.y + q[1] * (box.hi.y - box.lo.y),
                 box.lo.z + q[2] * (box.hi.z - box.lo.z)};
        const MeshPoint s = closest_surface_point(mesh, p);
        propagation.run(s.tri, crps.to_2d(s.tri, s.point), reach * (1 + 1e-9) + 1e-300,
                        windows);
        std::stable_sort(windows.begin(), windows.end(),
                         [](const GeodesicWindow &a, const GeodesicWindow &b) {
                             return a.face < b.face;
                         });
        for (size_t i = 0; i < windows.size();) {
            size_t j = i;
            while (j < windows.size() && windows[j].face == windows[i].face) ++j;
            const TriId t = windows[i].face;
            for (int c = 0; c < 3; ++c) {
                double d = distance_from_windows(windows.data() + i, windows.data() + j,
                                                 crps.frame(t).v[c]);
                d = std::min(d, propagation.vertex_distance(gmesh.corners(t)[c]));
                double &best = distance[3 * size_t(t) + c];
                best = std::min(best, d);
            }
            i = j;
        }
    }
    std::vector<double> out(distance.size());
    for (size_t k = 0; k < out.size(); ++k)
        out[k] = std::isfinite(distance[k]) ? inside(distance[k] / L - r.within, r.blend)
                                            : 0.0;
    return out;
}

std::vector<double> attribute_values(const RegionSpec &r, const TriangleMesh &mesh,
                                     const std::string &preset, const std::string &path) {
    for (const auto &[name, values] : mesh.vertex_attributes) {
        if (name != r.attribute) continue;
        std::vector<double> out(3 * mesh.num_triangles());
        for (TriId t = 0; t < mesh.num_triangles(); ++t)
            for (int c = 0; c < 3; ++c)
                out[3 * size_t(t) + c] =
                    std::clamp(double(values[mesh.triangles[t][c]]), 0.0, 1.0);
        return out;
    }
    std::string names;
    for (const auto &[name, values] : mesh.vertex_attributes)
        names += (names.empty() ? "" : ", ") + name;
    throw InputError(preset, 0, path + ".attribute",
                     "the mesh has no vertex attribute '" + r.attribute + "' (" +
                         (names.empty() ? "it has none; only PLY vertex properties are "
                                          "read as attributes"
                                        : "it has: " + names) +
                         ")");
}

std::vector<double> texture_values(const RegionSpec &r, const TriangleMesh &mesh,
                                   const std::string &preset, const std::string &path) {
    if (mesh.corner_uvs.size() != 3 * mesh.num_triangles())
        throw InputError(preset, 0, path + ".texture",
                         "the mesh has no texture coordinates (UVs)");
    OIIO::ImageBuf image(r.texture);
    if (!image.read(0, 0, true, OIIO::TypeDesc::FLOAT))
        throw InputError(r.texture, 0, path + ".texture",
                         "cannot read the image: " + image.geterror());
    const int channels = image.nchannels();
    if (r.channel >= channels)
        throw InputError(preset, 0, path + ".channel",
                         "the image has " + std::to_string(channels) + " channel(s)");
    std::vector<float> pixel(size_t(channels), 0.f);
    std::vector<double> out(3 * mesh.num_triangles());
    for (size_t k = 0; k < out.size(); ++k) {
        const Vec2d uv = mesh.corner_uvs[k];
        // UV v runs up the image, rows run down; the texture repeats outside [0, 1].
        image.interppixel_NDC(float(uv.x), float(1.0 - uv.y), pixel.data(),
                              OIIO::ImageBuf::WrapPeriodic);
        out[k] = std::clamp(double(pixel[size_t(r.channel)]), 0.0, 1.0);
    }
    return out;
}

}  // namespace

SurfaceControl::SurfaceControl(const ControlSpec &spec, const TriangleMesh &mesh,
                               const Crps &crps, const std::string &preset,
                               const TriangleMesh *data_mesh)
    : m_spec(spec), m_crps(&crps) {
    const bool transfer = data_mesh && data_mesh != &mesh;
    const TriangleMesh &data = transfer ? *data_mesh : mesh;
    std::vector<MeshPoint> map;  // built on first use
    auto carried = [&](std::vector<double> values) {
        if (!transfer) return values;
        if (map.empty()) map = closest_source_points(data, mesh);
        return transfer_corner_values(map, values);
    };
    const size_t n = spec.regions.size();
    m_corner.resize(n);
    std::vector<bool> done(n, false);
    // Operands first (parse_regions refused cycles).
    std::function<void(size_t)> resolve = [&](size_t i) {
        if (done[i]) return;
        const RegionSpec &r = spec.regions[i];
        for (int o : r.operands) resolve(size_t(o));
        const std::string path = "regions." + spec.region_names[i];
        std::vector<double> &out = m_corner[i];
        switch (r.kind) {
            case RegionSpec::Kind::height:
                out = height_values(r, mesh);
                break;
            case RegionSpec::Kind::near:
                out = near_values(r, mesh, crps);
                break;
            case RegionSpec::Kind::attribute:
                out = carried(attribute_values(r, data, preset, path));
                break;
            case RegionSpec::Kind::texture:
                out = carried(texture_values(r, data, preset, path));
                break;
            case RegionSpec::Kind::any:
            case RegionSpec::Kind::all: {
                const bool any = r.kind == RegionSpec::Kind::any;
                out = m_corner[r.operands[0]];
                for (size_t k = 1; k < r.operands.size(); ++k) {
                    const std::vector<double> &o = m_corner[r.operands[k]];
                    for (size_t c = 0; c < out.size(); ++c)
                        out[c] = any ? std::max(out[c], o[c]) : std::min(out[c], o[c]);
                }
                break;
            }
            case RegionSpec::Kind::negate:
                out = m_corner[r.operands[0]];
                for (double &v : out) v = 1 - v;
                break;
        }
        done[i] = true;
    };
    for (size_t i = 0; i < n; ++i) resolve(i);
}

double SurfaceControl::region(int i, TriId t, Vec2d p) const {
    const Vec3d b = m_crps->to_barycentric(t, p);
    const double *c = &m_corner[size_t(i)][3 * size_t(t)];
    // Barycentrics clamped: a point on an edge may come out a rounding error outside.
    const double b0 = std::max(b.x, 0.0), b1 = std::max(b.y, 0.0),
                 b2 = std::max(b.z, 0.0);
    const double sum = b0 + b1 + b2;
    if (!(sum > 0)) return c[0];
    return std::clamp((b0 * c[0] + b1 * c[1] + b2 * c[2]) / sum, 0.0, 1.0);
}

double SurfaceControl::value(const LocalValue &v, TriId t, Vec2d p) const {
    double x = v.value;
    for (const auto &[region_index, target] : v.in)
        x += (target - x) * region(region_index, t, p);
    return x;
}

double SurfaceControl::triangle_mean(const LocalValue &v, TriId t) const {
    const auto &f = m_crps->frame(t);
    return (value(v, t, f.v[0]) + value(v, t, f.v[1]) + value(v, t, f.v[2])) / 3.0;
}

double SurfaceControl::mask(const MaskSpec &m, TriId t, Vec2d p) const {
    const double v = region(m.region, t, p);
    return m.inside ? v : 1.0 - v;
}

int SurfaceControl::draw_masked_type(int type, TriId t, Vec2d p, CounterRng &rng) const {
    for (const MaskSpec &m : m_spec.masks) {
        if (type != m.type) continue;
        if (rng.uniform() >= mask(m, t, p)) type = m.otherwise;
    }
    return type;
}

int SurfaceControl::masked_type_where_zero(int type, TriId t, Vec2d p) const {
    for (const MaskSpec &m : m_spec.masks)
        if (type == m.type && mask(m, t, p) <= 0) type = m.otherwise;
    return type;
}

}  // namespace pelage::sim
