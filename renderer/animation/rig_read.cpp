// Reading a rig: assimp imports the file exactly as read_assimp() does (same flags, same
// walk), and everything posing needs is copied out, so the importer is gone before the
// first frame.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <mutex>
#include <new>
#include <set>

#include "renderer/animation/rig.h"
#include "renderer/animation/rig_data.h"
#include "sim/core/input_error.h"
#include "sim/mesh/mesh_io.h"
#include "sim/mesh/mesh_objects.h"

namespace pelage::renderer {
namespace {

using sim::assimp_walk::name_of;

sim::Vec3d vec(const aiVector3D &v) { return {double(v.x), double(v.y), double(v.z)}; }
Quat quat(const aiQuaternion &q) {
    return {double(q.w), double(q.x), double(q.y), double(q.z)};
}

std::string lower_extension(const std::string &path) {
    const auto dot = path.find_last_of('.');
    const auto slash = path.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
        return "";
    std::string e = path.substr(dot + 1);
    for (char &c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

// Preorder: a node's parent is always listed before it.
void add_nodes(const aiNode &node, int parent, RigData &d,
               std::map<const aiNode *, int> &index) {
    RigData::Node n;
    n.name = name_of(node.mName);
    n.parent = parent;
    n.rest = Transform::from(node.mTransformation);
    aiVector3D s, t;
    aiQuaternion r;
    node.mTransformation.Decompose(s, r, t);
    n.rest_trs = {vec(t), quat(r), vec(s)};
    const int me = int(d.nodes.size());
    index[&node] = me;
    d.nodes.push_back(std::move(n));
    for (unsigned c = 0; c < node.mNumChildren; ++c)
        add_nodes(*node.mChildren[c], me, d, index);
}

}  // namespace

Rig Rig::read(const std::string &mesh_ref) {
    const sim::MeshSpec spec = sim::parse_mesh_spec(mesh_ref);
    const std::string &path = spec.path;
    const std::string ext = lower_extension(path);
    if (mesh_ref.rfind("procedural:", 0) == 0 || ext == "off" || ext == "ply" ||
        ext == "obj" || !sim::is_mesh_extension(ext))
        throw InputError(path, 0, "",
                         "has no animation: skins, morph targets and clips come from "
                         "files read through assimp (glTF, FBX, Collada, ...)");
    if (!std::ifstream(path, std::ios::binary))
        throw InputError(path, 0, "", "cannot open file");
    Assimp::Importer importer;
    sim::assimp_walk::configure(importer);
    const aiScene *scene = nullptr;
    try {
        scene = importer.ReadFile(path, sim::assimp_walk::import_flags);
    } catch (const std::bad_alloc &) {
        throw InputError(path, 0, "", "out of memory while reading the file");
    } catch (const std::exception &e) {
        throw InputError(path, 0, "", std::string("cannot read the file: ") + e.what());
    }
    if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
        throw InputError(
            path, 0, "",
            "cannot read the file: " + std::string(importer.GetErrorString()));

    auto d = std::make_unique<RigData>();
    d->path = path;
    std::map<const aiNode *, int> node_index;
    add_nodes(*scene->mRootNode, -1, *d, node_index);
    // Bones and channels name their nodes; the first node of a name wins (glTF
    // importers make them unique).
    std::map<std::string, int> by_name;
    for (size_t i = 0; i < d->nodes.size(); ++i)
        by_name.emplace(d->nodes[i].name, int(i));

    const sim::assimp_walk::SceneWalk walk(*scene, spec.object);
    if (!spec.object.empty() && !walk.matched())
        sim::fail_unknown_object(path, spec.object, walk.names());

    const bool gltf = ext == "gltf" || ext == "glb";
    size_t renormalised = 0;
    double lowest_sum = 1e300, highest_sum = -1e300;
    // --- The pieces, in read_assimp()'s order and with its filter ---
    std::map<std::string, std::vector<size_t>> pieces_of_mesh_name;
    for (const sim::assimp_walk::Instance &in : walk.instances()) {
        const aiMesh &m = *scene->mMeshes[in.mesh];
        if (!(m.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
        const std::string label =
            "mesh " + std::to_string(in.mesh) +
            (m.mName.length > 0 ? " (\"" + name_of(m.mName) + "\")" : std::string());
        RigData::Piece p;
        p.node = node_index.at(in.node);
        p.vertices.reserve(m.mNumVertices);
        for (unsigned v = 0; v < m.mNumVertices; ++v)
            p.vertices.push_back(vec(m.mVertices[v]));
        for (unsigned k = 0; k < m.mNumAnimMeshes; ++k) {
            const aiAnimMesh *a = m.mAnimMeshes[k];
            std::vector<sim::Vec3d> target = p.vertices;  // a target without positions
            if (a && a->mVertices && a->mNumVertices == m.mNumVertices)
                for (unsigned v = 0; v < m.mNumVertices; ++v)
                    target[v] = vec(a->mVertices[v]);
            p.targets.push_back(std::move(target));
            p.target_weights.push_back(a ? double(a->mWeight) : 0.0);
        }
        // --- Skin: each bone's node and inverse bind matrix, each vertex's weights ---
        if (m.mNumBones > 0) {
            std::vector<std::vector<RigData::Influence>> per_vertex(m.mNumVertices);
            for (unsigned b = 0; b < m.mNumBones; ++b) {
                const aiBone &bone = *m.mBones[b];
                const auto it = by_name.find(name_of(bone.mName));
                if (it == by_name.end())
                    throw InputError(path, 0, "",
                                     label + ": bone \"" + name_of(bone.mName) +
                                         "\" names no node of the file");
                p.bones.push_back({it->second, Transform::from(bone.mOffsetMatrix)});
                for (unsigned w = 0; w < bone.mNumWeights; ++w) {
                    const aiVertexWeight &vw = bone.mWeights[w];
                    if (vw.mVertexId >= m.mNumVertices || !std::isfinite(vw.mWeight))
                        throw InputError(path, 0, "",
                                         label + ": bone \"" + name_of(bone.mName) +
                                             "\" has a bad weight (vertex " +
                                             std::to_string(vw.mVertexId) + ")");
                    if (vw.mWeight != 0)
                        per_vertex[vw.mVertexId].push_back({b, double(vw.mWeight)});
                }
            }
            p.influence_begin.push_back(0);
            for (unsigned v = 0; v < m.mNumVertices; ++v) {
                double sum = 0;
                for (const RigData::Influence &i : per_vertex[v]) sum += i.weight;
                // glTF 2.0 §3.7.3.3: a vertex's weights sum to 1; quantized weights miss
                // it by a few 1/255ths, anything further is a broken skin. FBX and
                // Collada make no such promise (DCC tools normalise on import, and
                // leave a vertex without weights on its mesh's node): so does pelage,
                // and says how many it changed.
                const bool off = !(std::abs(sum - 1) <= 0.02);
                if (off && (gltf || !(sum >= 0) || !std::isfinite(sum)))
                    throw InputError(path, 0, "",
                                     label + " vertex " + std::to_string(v) +
                                         ": its bone weights sum to " +
                                         std::to_string(sum) + ", not 1");
                if (off) {
                    ++renormalised;
                    lowest_sum = std::min(lowest_sum, sum);
                    highest_sum = std::max(highest_sum, sum);
                }
                if (sum > 0)
                    for (RigData::Influence i : per_vertex[v]) {
                        i.weight /= sum;
                        p.influences.push_back(i);
                    }
                p.influence_begin.push_back(uint32_t(p.influences.size()));
            }
        }
        d->num_vertices += p.vertices.size();
        pieces_of_mesh_name[name_of(m.mName)].push_back(d->pieces.size());
        d->pieces.push_back(std::move(p));
    }
    if (d->pieces.empty())
        throw InputError(path, 0, "",
                         (spec.object.empty() ? std::string("the file")
                                              : "object \"" + spec.object + "\"") +
                             " holds no triangles");

    // --- Clips: keys in seconds ---
    for (unsigned a = 0; a < scene->mNumAnimations; ++a) {
        const aiAnimation &anim = *scene->mAnimations[a];
        RigData::Clip clip;
        clip.name = name_of(anim.mName);
        if (clip.name.empty()) clip.name = "clip" + std::to_string(a);
        // assimp gives 0 when the file does not say; its own convention is then 25.
        const double tps = anim.mTicksPerSecond > 0 ? anim.mTicksPerSecond : 25.0;
        // glTF stores key times as float seconds, which assimp turns into float
        // milliseconds, moving a key by up to a microsecond; the nearest float to the
        // time in seconds is the file's own time again.
        auto seconds = [&](double ticks) {
            return gltf ? double(float(ticks / tps)) : ticks / tps;
        };
        clip.duration = seconds(anim.mDuration);
        auto channel_node = [&](const aiString &name) {
            const auto it = by_name.find(name_of(name));
            if (it == by_name.end())
                throw InputError(path, 0, "",
                                 "clip \"" + clip.name + "\" animates \"" +
                                     name_of(name) + "\", which is no node of the file");
            return it->second;
        };
        for (unsigned c = 0; c < anim.mNumChannels; ++c) {
            const aiNodeAnim &na = *anim.mChannels[c];
            RigData::Channel ch;
            ch.node = channel_node(na.mNodeName);
            for (unsigned k = 0; k < na.mNumPositionKeys; ++k)
                ch.position.push_back({seconds(na.mPositionKeys[k].mTime),
                                       vec(na.mPositionKeys[k].mValue)});
            for (unsigned k = 0; k < na.mNumRotationKeys; ++k)
                ch.rotation.push_back({seconds(na.mRotationKeys[k].mTime),
                                       quat(na.mRotationKeys[k].mValue)});
            for (unsigned k = 0; k < na.mNumScalingKeys; ++k)
                ch.scale.push_back(
                    {seconds(na.mScalingKeys[k].mTime), vec(na.mScalingKeys[k].mValue)});
            clip.channels.push_back(std::move(ch));
        }
        for (unsigned c = 0; c < anim.mNumMorphMeshChannels; ++c) {
            const aiMeshMorphAnim &ma = *anim.mMorphMeshChannels[c];
            RigData::MorphChannel mc;
            mc.node = channel_node(ma.mName);
            for (unsigned k = 0; k < ma.mNumKeys; ++k) {
                const aiMeshMorphKey &key = ma.mKeys[k];
                std::vector<std::pair<uint32_t, double>> w;
                for (unsigned i = 0; i < key.mNumValuesAndWeights; ++i)
                    w.push_back({key.mValues[i], key.mWeights[i]});
                mc.keys.push_back({seconds(key.mTime), std::move(w)});
            }
            clip.morphs.push_back(std::move(mc));
        }
        d->clip_names.push_back(clip.name);
        d->clips.push_back(std::move(clip));
    }
    if (d->clips.empty())
        throw InputError(path, 0, "", "the file has no animation clips");
    // Said once per file and process: every frame reads the rig again.
    static std::mutex noted_mutex;
    static std::set<std::string> noted;
    const std::lock_guard<std::mutex> lock(noted_mutex);
    if (renormalised > 0 && noted.insert(path).second)
        std::fprintf(stderr,
                     "pelage: %s: the bone weights of %zu vertices summed to %.3g-%.3g; "
                     "scaled to sum to 1 (those without any follow their mesh's node)\n",
                     path.c_str(), renormalised, lowest_sum, highest_sum);
    return Rig(std::move(d));
}

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
