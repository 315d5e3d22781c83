// Object-space position of a hit, for procedural plugins (worley, perlin): the mesh view
// is only valid during create(), so the plugin keeps its own copy. Object space means the
// pattern follows the object's transform (a turntable does not make it swim), though not
// a deformation of the mesh — the CM pattern, attached to (triangle, CRPS point), does.
#pragma once

#include <cstdint>
#include <vector>

#include "shader/pelage_shader.h"

namespace pelage::shader::sdk {

class ObjectSpacePositions {
  public:
    void copy_from(const PelageMeshView &mesh) {
        m_positions.assign(mesh.positions,
                           mesh.positions + 3 * size_t(mesh.num_vertices));
        m_triangles.assign(mesh.triangles,
                           mesh.triangles + 3 * size_t(mesh.num_triangles));
    }
    // False when the primitive is not a triangle of this mesh.
    bool position(const PelageHit &hit, float p[3]) const {
        if (size_t(hit.primitive_id) * 3 + 2 >= m_triangles.size()) return false;
        const uint32_t *t = &m_triangles[3 * size_t(hit.primitive_id)];
        const float b0 = 1 - hit.b1 - hit.b2;
        for (int k = 0; k < 3; ++k)
            p[k] = b0 * m_positions[3 * t[0] + k] + hit.b1 * m_positions[3 * t[1] + k] +
                   hit.b2 * m_positions[3 * t[2] + k];
        return true;
    }

  private:
    std::vector<float> m_positions;
    std::vector<uint32_t> m_triangles;
};

// smoothstep(e0, e1, x): 0 below e0, 1 above e1, C1 in between.
inline float smoothstep(float e0, float e1, float x) {
    if (e1 <= e0) return x < e0 ? 0.0f : 1.0f;
    float t = (x - e0) / (e1 - e0);
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    return t * t * (3 - 2 * t);
}

}  // namespace pelage::shader::sdk
