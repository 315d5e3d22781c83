#include "renderer/look/look_objects.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "sim/mesh/mesh_io.h"

namespace pelage::renderer {
namespace {

// A triangle by its corners' positions, whatever their order: the same triangle read
// with the whole file and with one object has the same key (both reads place it alike;
// neither is cleaned, as welding depends on what else is read).
uint64_t triangle_key(const sim::TriangleMesh &m, const std::array<sim::VertId, 3> &t) {
    uint64_t h[3];
    for (int c = 0; c < 3; ++c) {
        const sim::Vec3d &p = m.positions[t[c]];
        uint64_t x = 1469598103934665603ull;
        for (double v : {p.x, p.y, p.z}) {
            uint64_t bits;
            std::memcpy(&bits, &v, sizeof bits);
            x = (x ^ bits) * 1099511628211ull;
            x ^= x >> 29;
        }
        h[c] = x;
    }
    std::sort(h, h + 3);
    return (h[0] * 0x9e3779b97f4a7c15ull) ^ (h[1] * 0xc2b2ae3d27d4eb4full) ^ h[2];
}

struct Candidate {
    LookObject object;
    std::vector<uint64_t> keys;  // sorted, unique
    size_t order = 0;            // in the file's names
};

Candidate measure(const std::string &path, const std::string &name, const double up[3]) {
    Candidate c;
    c.object.name = name;
    const sim::TriangleMesh m = sim::read_mesh(path, nullptr, name);
    c.object.materials = !m.materials.empty();
    for (const sim::MeshMaterial &mm : m.materials)
        if (!mm.diffuse_texture.empty() && !std::filesystem::exists(mm.diffuse_texture))
            c.object.missing_texture = mm.diffuse_texture;
    sim::Vec3d normal_sum{0, 0, 0}, centroid{0, 0, 0}, lo{1e300, 1e300, 1e300},
        hi{-1e300, -1e300, -1e300};
    for (const auto &t : m.triangles) {
        const sim::Vec3d a = m.positions[t[0]], b = m.positions[t[1]],
                         d = m.positions[t[2]];
        const sim::Vec3d n = cross(b - a, d - a) * 0.5;  // area-weighted normal
        const double area = length(n);
        c.object.area += area;
        normal_sum = normal_sum + n;
        centroid = centroid + (a + b + d) * (area / 3);
        c.keys.push_back(triangle_key(m, t));
    }
    // The corners only: a file's reader may keep every vertex of the file.
    std::vector<sim::Vec3d> corners;
    for (const auto &t : m.triangles)
        for (sim::VertId v : t) corners.push_back(m.positions[v]);
    for (const sim::Vec3d &p : corners) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    std::sort(c.keys.begin(), c.keys.end());
    c.keys.erase(std::unique(c.keys.begin(), c.keys.end()), c.keys.end());
    // Flat: the area-weighted normals all but agree (a closed or curved surface's
    // cancel), and no vertex leaves their plane by 1 % of the object's size.
    const double normal_length = length(normal_sum);
    if (c.object.area > 0 && normal_length >= 0.99 * c.object.area) {
        const sim::Vec3d n = normal_sum / normal_length;
        centroid = centroid / c.object.area;
        const double size = length(hi - lo);
        bool in_plane = true;
        for (const sim::Vec3d &p : corners)
            in_plane &= std::abs(dot(p - centroid, n)) <= 0.01 * size;
        c.object.flat = in_plane;
        const sim::Vec3d u{up[0], up[1], up[2]};
        c.object.flat_height = dot(centroid, u) / length(u);
        c.object.flat_facing_up =
            std::abs(dot(n, u)) >= std::cos(8 * M_PI / 180) * length(u);
    }
    return c;
}

}  // namespace

LookObjects choose_look_objects(const std::string &path, const double up[3],
                                size_t max_names) {
    sim::MeshReadStats read;
    const sim::TriangleMesh whole = sim::read_mesh(path, &read);
    const std::vector<std::string> &names = read.object_names;
    LookObjects out;
    if (names.size() < 2) return out;
    std::vector<uint64_t> all;
    for (const auto &t : whole.triangles) all.push_back(triangle_key(whole, t));
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());

    std::vector<Candidate> candidates;
    for (size_t i = 0; i < names.size() && i < max_names; ++i) {
        Candidate c = measure(path, names[i], up);
        c.order = i;
        if (c.keys.size() >= all.size() || c.keys.empty()) continue;  // all, or nothing
        candidates.push_back(std::move(c));
    }
    // Parents (a node over several meshes) hold another candidate: the parts are what
    // is chosen among. Of two names for the same triangles the first stands.
    std::vector<char> parent(candidates.size(), 0);  // holds another candidate
    for (size_t i = 0; i < candidates.size(); ++i)
        for (size_t j = 0; j < candidates.size() && !parent[i]; ++j) {
            if (i == j) continue;
            const auto &a = candidates[i].keys, &b = candidates[j].keys;
            if (b.size() > a.size() || (b.size() == a.size() && j > i)) continue;
            if (std::includes(a.begin(), a.end(), b.begin(), b.end())) parent[i] = 1;
        }
    // The animal: the largest part that is not flat.
    std::vector<size_t> parts, by_area;
    for (size_t i = 0; i < candidates.size(); ++i) {
        by_area.push_back(i);
        if (!parent[i]) parts.push_back(i);
    }
    auto larger = [&](size_t a, size_t b) {
        return candidates[a].object.area > candidates[b].object.area;
    };
    std::stable_sort(parts.begin(), parts.end(), larger);
    std::stable_sort(by_area.begin(), by_area.end(), larger);
    if (parts.empty()) return out;
    size_t animal = parts.front();
    for (size_t i : parts)
        if (!candidates[i].object.flat) {
            animal = i;
            break;
        }
    // The others: largest first, parents too (a node's own triangles come only with
    // it), each taken when it shares no triangle with the animal or one taken before.
    std::vector<uint64_t> taken = candidates[animal].keys;
    for (size_t i : by_area) {
        if (i == animal) continue;
        const auto &k = candidates[i].keys;
        std::vector<uint64_t> common;
        std::set_intersection(k.begin(), k.end(), taken.begin(), taken.end(),
                              std::back_inserter(common));
        if (!common.empty()) continue;
        out.others.push_back(candidates[i].object);
        std::vector<uint64_t> merged;
        std::merge(taken.begin(), taken.end(), k.begin(), k.end(),
                   std::back_inserter(merged));
        taken.swap(merged);
    }
    if (out.others.empty()) return {};  // one object after all
    out.animal = candidates[animal].object.name;
    out.left_out = all.size() - taken.size();
    // The others in the file's order, as a person reading the scene expects.
    std::stable_sort(out.others.begin(), out.others.end(),
                     [&](const LookObject &a, const LookObject &b) {
                         return std::find(names.begin(), names.end(), a.name) <
                                std::find(names.begin(), names.end(), b.name);
                     });
    return out;
}

}  // namespace pelage::renderer
