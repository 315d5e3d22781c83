// Posing a rig at a time: glTF 2.0 §3.11 (animations: linear interpolation, spherical
// linear for rotations; before the first key the first value, after the last the last),
// §3.7.2.2 (morph targets) and §3.7.3 (skins). In double precision throughout, so the
// pose is as exact as the file's floats.
#include <algorithm>
#include <cmath>

#include "renderer/animation/rig.h"
#include "renderer/animation/rig_data.h"
#include "sim/core/input_error.h"

namespace pelage::renderer {
namespace {

using sim::Vec3d;

// The keys around `t` and the blend between them: (i, i + 1, f), or (i, i, 0) at or
// beyond the ends. Keys are in increasing time (assimp sorts them).
template <class K>
void bracket(const std::vector<K> &keys, double t, size_t *i0, size_t *i1, double *f) {
    if (t <= keys.front().time || keys.size() == 1) {
        *i0 = *i1 = 0, *f = 0;
        return;
    }
    if (t >= keys.back().time) {
        *i0 = *i1 = keys.size() - 1, *f = 0;
        return;
    }
    const auto it = std::upper_bound(keys.begin(), keys.end(), t,
                                     [](double x, const K &k) { return x < k.time; });
    *i1 = size_t(it - keys.begin());
    *i0 = *i1 - 1;
    const double dt = keys[*i1].time - keys[*i0].time;
    *f = dt > 0 ? (t - keys[*i0].time) / dt : 0.0;
}

Vec3d sample(const std::vector<RigData::Key<Vec3d>> &keys, double t, Vec3d fallback) {
    if (keys.empty()) return fallback;
    size_t i0, i1;
    double f;
    bracket(keys, t, &i0, &i1, &f);
    return keys[i0].value * (1 - f) + keys[i1].value * f;
}

Quat normalized(Quat q) {
    const double n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    return n > 0 ? Quat{q.w / n, q.x / n, q.y / n, q.z / n} : Quat{};
}

// The shorter arc between two unit quaternions (q and −q are the same rotation).
Quat slerp(Quat a, Quat b, double f) {
    double d = a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z;
    if (d < 0) b = {-b.w, -b.x, -b.y, -b.z}, d = -d;
    double wa = 1 - f, wb = f;
    if (d < 1 - 1e-12) {  // nearer, sin θ loses the digits the weights need
        const double theta = std::acos(std::min(d, 1.0));
        const double s = std::sin(theta);
        wa = std::sin((1 - f) * theta) / s;
        wb = std::sin(f * theta) / s;
    }
    return normalized({wa * a.w + wb * b.w, wa * a.x + wb * b.x, wa * a.y + wb * b.y,
                       wa * a.z + wb * b.z});
}

Quat sample(const std::vector<RigData::Key<Quat>> &keys, double t, Quat fallback) {
    if (keys.empty()) return fallback;
    size_t i0, i1;
    double f;
    bracket(keys, t, &i0, &i1, &f);
    return slerp(normalized(keys[i0].value), normalized(keys[i1].value), f);
}

Vec3d apply(const Transform &m, Vec3d v) {
    return {m.a[0][0] * v.x + m.a[0][1] * v.y + m.a[0][2] * v.z + m.t[0],
            m.a[1][0] * v.x + m.a[1][1] * v.y + m.a[1][2] * v.z + m.t[1],
            m.a[2][0] * v.x + m.a[2][1] * v.y + m.a[2][2] * v.z + m.t[2]};
}

}  // namespace

Transform Trs::matrix() const {
    const Quat q = normalized(r);
    const double xx = q.x * q.x, yy = q.y * q.y, zz = q.z * q.z;
    const double xy = q.x * q.y, xz = q.x * q.z, yz = q.y * q.z;
    const double wx = q.w * q.x, wy = q.w * q.y, wz = q.w * q.z;
    const double rot[3][3] = {{1 - 2 * (yy + zz), 2 * (xy - wz), 2 * (xz + wy)},
                              {2 * (xy + wz), 1 - 2 * (xx + zz), 2 * (yz - wx)},
                              {2 * (xz - wy), 2 * (yz + wx), 1 - 2 * (xx + yy)}};
    const double sc[3] = {s.x, s.y, s.z};
    Transform m;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m.a[i][j] = rot[i][j] * sc[j];
    m.t[0] = t.x, m.t[1] = t.y, m.t[2] = t.z;
    return m;
}

std::vector<Vec3d> Rig::pose(int clip_index, double seconds,
                             std::vector<std::array<double, 9>> *normal_matrices) const {
    const RigData &d = *m;
    // The default pose is a clip without channels: the nodes stay where the file puts
    // them, the morph weights at the mesh's own.
    static const RigData::Clip no_channels{"the default pose", 0, {}, {}};
    const RigData::Clip &clip =
        clip_index == default_pose ? no_channels : d.clips.at(size_t(clip_index));
    // --- Every node's local transform at the time, then the global ones ---
    std::vector<Transform> global(d.nodes.size());
    for (size_t n = 0; n < d.nodes.size(); ++n) global[n] = d.nodes[n].rest;
    for (const RigData::Channel &ch : clip.channels) {
        const Trs &rest = d.nodes[size_t(ch.node)].rest_trs;
        global[size_t(ch.node)] =
            Trs{sample(ch.position, seconds, rest.t),
                sample(ch.rotation, seconds, rest.r), sample(ch.scale, seconds, rest.s)}
                .matrix();
    }
    for (size_t n = 0; n < d.nodes.size(); ++n)  // parents come first
        if (d.nodes[n].parent >= 0)
            global[n] = global[size_t(d.nodes[n].parent)] * global[n];

    std::vector<Vec3d> out;
    out.reserve(d.num_vertices);
    if (normal_matrices) normal_matrices->clear();
    for (const RigData::Piece &p : d.pieces) {
        // --- Morph weights: the channel on the piece's node, or the file's defaults ---
        std::vector<double> weights = p.target_weights;
        for (const RigData::MorphChannel &mc : clip.morphs) {
            if (mc.node != p.node || mc.keys.empty()) continue;
            size_t i0, i1;
            double f;
            bracket(mc.keys, seconds, &i0, &i1, &f);
            std::fill(weights.begin(), weights.end(), 0.0);
            for (const auto &[target, w] : mc.keys[i0].value)
                if (target < weights.size()) weights[target] += (1 - f) * w;
            for (const auto &[target, w] : mc.keys[i1].value)
                if (target < weights.size()) weights[target] += f * w;
        }
        // --- Skin matrices: each joint's global transform times its IBM ---
        std::vector<Transform> skin(p.bones.size());
        for (size_t b = 0; b < p.bones.size(); ++b)
            skin[b] = global[size_t(p.bones[b].node)] * p.bones[b].offset;
        for (size_t v = 0; v < p.vertices.size(); ++v) {
            Vec3d x = p.vertices[v];
            for (size_t k = 0; k < p.targets.size(); ++k)
                if (weights[k] != 0) x += (p.targets[k][v] - p.vertices[v]) * weights[k];
            // The vertex's map: its node's, or its joints' blend (linear blend skinning
            // blends the matrices, which is the same as blending the points).
            Transform m;
            if (p.bones.empty() || p.influence_begin[v] == p.influence_begin[v + 1]) {
                m = global[size_t(p.node)];
            } else {
                for (int r = 0; r < 3; ++r) {
                    m.t[r] = 0;
                    for (int c = 0; c < 3; ++c) m.a[r][c] = 0;
                }
                for (uint32_t i = p.influence_begin[v]; i < p.influence_begin[v + 1];
                     ++i) {
                    const Transform &s = skin[p.influences[i].bone];
                    const double w = p.influences[i].weight;
                    for (int r = 0; r < 3; ++r) {
                        m.t[r] += w * s.t[r];
                        for (int c = 0; c < 3; ++c) m.a[r][c] += w * s.a[r][c];
                    }
                }
            }
            const Vec3d posed = apply(m, x);
            if (normal_matrices) {
                // From the normal as read (through the node's transform in the file) to
                // the posed one.
                const Transform a = m * p.read_inverse;
                std::array<double, 9> n;
                const double sign = a.determinant() < 0 ? -1.0 : 1.0;
                for (int r = 0; r < 3; ++r)
                    for (int c = 0; c < 3; ++c) {
                        const int r1 = (r + 1) % 3, r2 = (r + 2) % 3;
                        const int c1 = (c + 1) % 3, c2 = (c + 2) % 3;
                        n[size_t(3 * r + c)] = sign * (a.a[r1][c1] * a.a[r2][c2] -
                                                       a.a[r1][c2] * a.a[r2][c1]);
                    }
                normal_matrices->push_back(n);
            }
            if (!is_finite(posed))
                throw InputError(
                    d.path, 0, "",
                    (clip_index == default_pose ? clip.name
                                                : "clip \"" + clip.name + "\" at " +
                                                      std::to_string(seconds) + " s") +
                        ": vertex " + std::to_string(out.size()) +
                        " has a non-finite position");
            out.push_back(posed);
        }
    }
    return out;
}

void unweld(const sim::MeshLoadReport &report, sim::TriangleMesh *mesh) {
    const auto &corners = report.clean.source_corners;
    PELAGE_CHECK(corners.size() == mesh->num_triangles());
    std::vector<Vec3d> positions(report.raw_vertices, Vec3d{0, 0, 0});
    for (size_t t = 0; t < corners.size(); ++t)
        for (int c = 0; c < 3; ++c)
            positions.at(corners[t][c]) = mesh->vertex(sim::TriId(t), c);
    mesh->positions = std::move(positions);
    mesh->triangles = corners;
    mesh->vertex_attributes.clear();  // per welded vertex: they do not follow
}

namespace {

// Corner normal `cn` turned by a vertex's normal transform (Rig::pose), unit length.
void turn_normal(const std::array<double, 9> &n, Vec3d *cn) {
    const Vec3d r{n[0] * cn->x + n[1] * cn->y + n[2] * cn->z,
                  n[3] * cn->x + n[4] * cn->y + n[5] * cn->z,
                  n[6] * cn->x + n[7] * cn->y + n[8] * cn->z};
    const double len = length(r);
    if (len > 0) *cn = r / len;
}

}  // namespace

void pose_default(const Rig &rig, const sim::MeshLoadReport &report,
                  sim::TriangleMesh *mesh) {
    std::vector<std::array<double, 9>> normal_matrices;
    const std::vector<Vec3d> posed = rig.pose(
        Rig::default_pose, 0, mesh->corner_normals.empty() ? nullptr : &normal_matrices);
    const std::vector<sim::VertId> &source = report.clean.source_vertex;
    PELAGE_CHECK(posed.size() == report.raw_vertices &&
                 source.size() == mesh->num_vertices());
    for (size_t v = 0; v < source.size(); ++v) mesh->positions[v] = posed.at(source[v]);
    // Each corner's normal goes with the vertex it was read as, as in a clip.
    const auto &corners = report.clean.source_corners;
    for (size_t t = 0; t < mesh->num_triangles() && !mesh->corner_normals.empty(); ++t)
        for (int c = 0; c < 3; ++c)
            turn_normal(normal_matrices.at(corners.at(t)[size_t(c)]),
                        &mesh->corner_normals[3 * t + size_t(c)]);
}

std::vector<float> rest_length_ratios(const std::vector<double> &rest_xyz,
                                      const sim::TriangleMesh &posed) {
    PELAGE_CHECK(rest_xyz.size() == 3 * posed.num_vertices());
    auto rest = [&](sim::VertId v) {
        return Vec3d{rest_xyz[3 * size_t(v)], rest_xyz[3 * size_t(v) + 1],
                     rest_xyz[3 * size_t(v) + 2]};
    };
    std::vector<float> out(posed.num_triangles(), 1.0f);
    for (size_t t = 0; t < out.size(); ++t) {
        const auto &tri = posed.triangles[t];
        const double rest_area =
            length(cross(rest(tri[1]) - rest(tri[0]), rest(tri[2]) - rest(tri[0])));
        const double posed_area = length(posed.face_normal_unnormalized(sim::TriId(t)));
        const double ratio = std::sqrt(rest_area / posed_area);
        if (rest_area > 0 && posed_area > 0 && std::isfinite(ratio))
            out[t] = float(ratio);
    }
    return out;
}

void pose_mesh(const Rig &rig, int clip, double seconds, sim::TriangleMesh *mesh) {
    std::vector<std::array<double, 9>> normal_matrices;
    std::vector<Vec3d> posed = rig.pose(clip, seconds, &normal_matrices);
    PELAGE_CHECK(posed.size() == mesh->num_vertices());
    mesh->positions = std::move(posed);
    for (size_t t = 0; t < mesh->num_triangles() && !mesh->corner_normals.empty(); ++t)
        for (int c = 0; c < 3; ++c)
            turn_normal(normal_matrices[mesh->triangles[t][c]],
                        &mesh->corner_normals[3 * t + size_t(c)]);
}

}  // namespace pelage::renderer
