// Smooth tangent fields from a few control vectors on the connection Laplacian of Sharp,
// Soliman and Crane, "The Vector Heat Method", ACM TOG 38(3) 2019 (discretisation §5,
// algorithm §6):
//   * every vertex gets a tangent basis: the angles of its outgoing edges, measured
//     counter-clockwise around the oriented normal and rescaled by 2π/Θ (Θ the sum of
//     its corner angles) so they fill a full turn (boundary and non-manifold vertices
//     keep their angles unscaled);
//   * the discrete Levi-Civita connection carries a vector across edge ij by keeping its
//     angle to the edge: r_ji = exp(i(φ_ij − φ_ji + π));
//   * L∇, the cotangent Laplacian with those rotations, is solved by sparse Cholesky
//     (Eigen's SimplicialLDLT), either as one backward-Euler step of the vector heat
//     flow, (M + t·L∇) X = X0 with the lumped mass M and t = h² for the mean edge length
//     h, or as the Dirichlet problem L∇ X = 0 with X held to the controls
//     (FieldInterpolation below); the directions of X are the field, every vector gets
//     one length.
// A control on a triangle spreads to its corners by its barycentric weights; each
// triangle's vector is the mean of its corners' vectors carried into its plane, and a
// control's own triangle takes the control's direction exactly. Triangles of a connected
// piece with no control, or where the controls cancel, get a zero vector (no preferred
// direction). Serial and deterministic.
#pragma once

#include <vector>

#include "sim/crps/crps.h"
#include "sim/crps/tangent_field.h"

namespace pelage::sim {

struct TangentControl {
    TriId tri = 0;
    Vec3d barycentric{1.0 / 3, 1.0 / 3, 1.0 / 3};  // the point in `tri`
    Vec3d direction;  // world direction, tangent to `tri` (any length but 0)
};

struct FieldInterpolation {
    // heat: the short-time vector heat flow above, which carries each control along
    // shortest geodesics, so between two controls the field turns within a few
    // triangles where their regions meet. harmonic: the smoothest field through the
    // controls, L∇ X = 0 with X held to the controls at their triangles' corners (the
    // connection Laplacian's Dirichlet problem, as in Knöppel, Crane, Pinkall, Schröder,
    // "Globally Optimal Direction Fields", SIGGRAPH 2013), which turns gradually between
    // them.
    enum class Method { heat, harmonic };
    Method method = Method::harmonic;
    double time_scale = 1.0;  // heat: t = time_scale · h²
};

// The field with vectors of length `magnitude`, in each triangle's CRPS frame. Throws
// std::runtime_error if the solver fails.
TangentField vector_heat_field(const Crps &crps,
                               const std::vector<TangentControl> &controls,
                               double magnitude, const FieldInterpolation &how = {});

// The direction of a 2D vector of triangle t's frame in world space (unit length, or
// zero for a zero vector), and back: the world vector's projection into t's frame.
Vec3d field_to_world(const Crps &crps, TriId t, Vec2d a);
Vec2d world_to_field(const Crps &crps, TriId t, Vec3d d);

}  // namespace pelage::sim
