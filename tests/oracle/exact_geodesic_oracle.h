// An independent reference for geodesic distances on a triangle mesh: CGAL's exact
// polyhedral shortest paths (Xin and Wang's improvement of Chen and Han's algorithm) on
// pelage's own TriangleMesh. Test-only; no CGAL type appears here, so a test including
// this header compiles against pelage's headers alone.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "sim/mesh/mesh.h"

namespace pelage::test {

// A point on the surface: barycentric weights of the corners 1 and 2 of
// mesh.triangles[tri]; corner 0 gets 1 - b1 - b2.
struct SurfaceLocation {
    sim::TriId tri = 0;
    double b1 = 0, b2 = 0;
};

class ExactGeodesicOracle {
  public:
    // Builds CGAL's Surface_mesh from `mesh`, face i being mesh.triangles[i]. A pinch
    // vertex (fans that share only the vertex) becomes one vertex per fan, so no geodesic
    // passes from one fan to another through it. Throws std::runtime_error when CGAL
    // cannot take a face as it is (an edge of three or more triangles, a repeated corner,
    // a winding that disagrees with a neighbour), since the face order would no longer
    // match pelage's.
    explicit ExactGeodesicOracle(const sim::TriangleMesh &mesh);
    ~ExactGeodesicOracle();
    ExactGeodesicOracle(ExactGeodesicOracle &&) noexcept;
    ExactGeodesicOracle &operator=(ExactGeodesicOracle &&) noexcept;

    // Geodesic distance from `source` to each target, from one sequence tree. A target in
    // another connected component than the source gets +infinity. Throws
    // std::invalid_argument for a triangle out of range or weights outside the triangle.
    std::vector<double> distances(const SurfaceLocation &source,
                                  std::span<const SurfaceLocation> targets) const;

    struct Nearest {
        uint32_t source;  // index into `sources`; sim::invalid_id when none is reachable
        double distance;  // +infinity when none is reachable
    };
    // For each target, the geodesically nearest source (the lowest index among equal
    // distances) and its distance. Each distance comes from a single-source tree on the
    // patch of the mesh around a source, grown until it certifies the answer; see the
    // .cpp for why CGAL's multi-source tree is not used.
    std::vector<Nearest> nearest(std::span<const SurfaceLocation> sources,
                                 std::span<const SurfaceLocation> targets) const;

    // The 3D point of `l` as CGAL computes it on its own face (tests of the corner
    // mapping compare it with pelage's interpolation).
    sim::Vec3d position(const SurfaceLocation &l) const;

    size_t num_triangles() const;
    // How many vertices were added for the extra fans of pinch vertices.
    size_t split_vertices() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

}  // namespace pelage::test
