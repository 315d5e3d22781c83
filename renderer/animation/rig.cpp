// The rig's queries (rig.h): its clips, what they move, and a clip's time at a scene
// time.
#include "renderer/animation/rig.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "renderer/animation/rig_data.h"
#include "sim/core/input_error.h"

namespace pelage::renderer {

Rig::Rig(std::unique_ptr<RigData> d) : m(std::move(d)) {}
Rig::Rig(Rig &&) noexcept = default;
Rig &Rig::operator=(Rig &&) noexcept = default;
Rig::~Rig() = default;

const std::string &Rig::path() const { return m->path; }
const std::vector<std::string> &Rig::clip_names() const { return m->clip_names; }
double Rig::duration_seconds(int clip) const {
    return m->clips.at(size_t(clip)).duration;
}
size_t Rig::num_vertices() const { return m->num_vertices; }
bool Rig::skinned() const {
    for (const RigData::Piece &p : m->pieces)
        if (!p.bones.empty()) return true;
    return false;
}

size_t Rig::num_bones() const {
    std::set<int> joints;
    for (const RigData::Piece &p : m->pieces)
        for (const RigData::Bone &b : p.bones) joints.insert(b.node);
    return joints.size();
}
size_t Rig::num_morph_targets() const {
    size_t n = 0;
    for (const RigData::Piece &p : m->pieces) n += p.targets.size();
    return n;
}

int Rig::clip(const std::string &name, const std::string &field) const {
    for (size_t i = 0; i < m->clip_names.size(); ++i)
        if (m->clip_names[i] == name) return int(i);
    std::string list;
    for (const std::string &n : m->clip_names)
        list += (list.empty() ? "\"" : ", \"") + n + "\"";
    throw InputError(m->path, 0, field,
                     "no clip named \"" + name + "\" (the file's clips: " + list + ")");
}

bool Rig::moves_mesh(int clip) const {
    const RigData::Clip &c = m->clips.at(size_t(clip));
    // The nodes whose motion reaches a vertex: every bone and its ancestors, and the
    // ancestors of every node that places a mesh without bones.
    std::vector<char> reaches(m->nodes.size(), 0);
    auto mark = [&](int n) {
        for (; n >= 0 && !reaches[size_t(n)]; n = m->nodes[size_t(n)].parent)
            reaches[size_t(n)] = 1;
    };
    for (const RigData::Piece &p : m->pieces) {
        if (p.bones.empty()) mark(p.node);
        for (const RigData::Bone &b : p.bones) mark(b.node);
    }
    for (const RigData::Channel &ch : c.channels)
        if (reaches[size_t(ch.node)]) return true;
    for (const RigData::MorphChannel &mc : c.morphs)
        for (const RigData::Piece &p : m->pieces)
            if (p.node == mc.node && !p.targets.empty()) return true;
    return false;
}

double clip_time(double seconds, double duration, bool loop) {
    if (!(duration > 0)) return 0;
    if (loop) {
        const double t = std::fmod(seconds, duration);
        return t < 0 ? t + duration : t;
    }
    return std::min(std::max(seconds, 0.0), duration);
}

}  // namespace pelage::renderer
