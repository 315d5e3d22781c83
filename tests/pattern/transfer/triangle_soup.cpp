#include "tests/pattern/transfer/triangle_soup.h"

#include <cmath>
#include <cstdio>
#include <deque>
#include <random>
#include <stdexcept>

#include "sim/crps/surface.h"

namespace pelage::test {

TriangleSoup make_triangle_soup(const sim::TriangleMesh &source, double offset_relative,
                                double min_separation_relative, uint64_t seed) {
    const sim::Surface s = sim::build_surface(source);
    const sim::Topology &topo = s.crps.topology();
    const size_t nt = s.mesh.num_triangles();
    const sim::Bounds3 box = s.mesh.bounds();
    const double diag = box.diagonal();
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> gauss(0, 1);
    std::uniform_int_distribution<int> size_of(1, 3);

    TriangleSoup soup;
    std::vector<uint32_t> piece_of(nt, UINT32_MAX);
    // The offsets already given to pieces that hold each source vertex.
    std::vector<std::vector<sim::Vec3d>> offsets_at(s.mesh.num_vertices());
    for (sim::TriId start = 0; start < nt; ++start) {
        if (piece_of[start] != UINT32_MAX) continue;
        const uint32_t id = uint32_t(soup.pieces++);
        // Breadth first across edges, up to the piece's size.
        std::vector<sim::TriId> tris;
        std::deque<sim::TriId> queue{start};
        piece_of[start] = id;
        const size_t want = size_t(size_of(rng));
        while (!queue.empty() && tris.size() < want) {
            const sim::TriId t = queue.front();
            queue.pop_front();
            tris.push_back(t);
            for (int k = 0; k < 3; ++k) {
                const sim::TriId n = topo.across(t, k);
                if (n == sim::invalid_id || piece_of[n] != UINT32_MAX) continue;
                if (tris.size() + queue.size() >= want) break;
                piece_of[n] = id;
                queue.push_back(n);
            }
        }
        for (sim::TriId t : queue) tris.push_back(t);  // claimed: part of the piece
        // One offset for the whole piece, far enough from its neighbours'.
        sim::Vec3d offset{0, 0, 0};
        for (int attempt = 0;; ++attempt) {
            const sim::Vec3d d{gauss(rng), gauss(rng), gauss(rng)};
            offset = normalize(d) * (offset_relative * diag);
            bool apart = true;
            for (sim::TriId t : tris)
                for (sim::VertId v : s.mesh.triangles[t])
                    for (const sim::Vec3d &o : offsets_at[v])
                        apart &= length(o - offset) >= min_separation_relative * diag;
            if (apart) break;
            if (attempt > 10000) throw std::runtime_error("no separated offset found");
        }
        // The piece's own copies of its vertices.
        std::vector<std::pair<sim::VertId, sim::VertId>> copies;
        auto copy_of = [&](sim::VertId v) {
            for (const auto &[from, to] : copies)
                if (from == v) return to;
            const sim::VertId to = sim::VertId(soup.mesh.positions.size());
            soup.mesh.positions.push_back(s.mesh.positions[v] + offset);
            offsets_at[v].push_back(offset);
            copies.push_back({v, to});
            return to;
        };
        for (sim::TriId t : tris) {
            const auto &tri = s.mesh.triangles[t];
            soup.mesh.triangles.push_back(
                {copy_of(tri[0]), copy_of(tri[1]), copy_of(tri[2])});
            soup.piece.push_back(id);
        }
    }
    // Tiny triangles just outside the middle of each face of the box: they touch
    // nothing, and are far smaller than any cell.
    const sim::Vec3d centre = (box.lo + box.hi) * 0.5, half = (box.hi - box.lo) * 0.5;
    const double edge = 0.005 * diag, gap = 0.02 * diag;
    for (int axis = 0; axis < 3; ++axis)
        for (int sign = -1; sign <= 1; sign += 2) {
            sim::Vec3d n{0, 0, 0}, u{0, 0, 0}, w{0, 0, 0};
            const double h = axis == 0 ? half.x : axis == 1 ? half.y : half.z;
            (axis == 0 ? n.x : axis == 1 ? n.y : n.z) = sign;
            (axis == 0 ? u.y : axis == 1 ? u.z : u.x) = edge;
            (axis == 0 ? w.z : axis == 1 ? w.x : w.y) = edge;
            const sim::Vec3d p = centre + n * (h + gap);
            const sim::VertId v = sim::VertId(soup.mesh.positions.size());
            soup.mesh.positions.push_back(p);
            soup.mesh.positions.push_back(p + u);
            soup.mesh.positions.push_back(p + w);
            soup.mesh.triangles.push_back({v, v + 1, v + 2});
            soup.piece.push_back(uint32_t(soup.pieces++));
            ++soup.floating;
        }
    return soup;
}

void write_off_exact(const std::string &path, const sim::TriangleMesh &mesh) {
    FILE *f = std::fopen(path.c_str(), "w");
    if (!f) throw std::runtime_error("cannot write " + path);
    std::fprintf(f, "OFF\n%zu %zu 0\n", mesh.num_vertices(), mesh.num_triangles());
    for (const sim::Vec3d &p : mesh.positions)
        std::fprintf(f, "%.17g %.17g %.17g\n", p.x, p.y, p.z);
    for (const auto &t : mesh.triangles)
        std::fprintf(f, "3 %u %u %u\n", t[0], t[1], t[2]);
    std::fclose(f);
}

}  // namespace pelage::test
