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

bool has_animation_format(const std::string &mesh_ref, const std::string &ext) {
    return mesh_ref.rfind("procedural:", 0) != 0 && ext != "off" && ext != "ply" &&
           ext != "obj" && sim::is_mesh_extension(ext);
}

// The format check before any reading: only files read through assimp carry animation.
void check_has_animation(const std::string &mesh_ref, const std::string &path,
                         const std::string &ext) {
    if (!has_animation_format(mesh_ref, ext))
        throw InputError(path, 0, "",
                         "has no animation: skins, morph targets and clips come from "
                         "files read through assimp (glTF, FBX, Collada, ...)");
}

// The file through `importer`, as read_assimp() reads it; the scene lives as long as
// the importer.
const aiScene &import_scene(Assimp::Importer &importer, const std::string &path) {
    if (!std::ifstream(path, std::ios::binary))
        throw InputError(path, 0, "", "cannot open file");
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
    return *scene;
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

// A mesh's morph targets as absolute positions, with their weights without a channel.
void read_morph_targets(const aiMesh &m, RigData::Piece &p) {
    for (unsigned k = 0; k < m.mNumAnimMeshes; ++k) {
        const aiAnimMesh *a = m.mAnimMeshes[k];
        std::vector<sim::Vec3d> target = p.vertices;  // a target without positions
        if (a && a->mVertices && a->mNumVertices == m.mNumVertices)
            for (unsigned v = 0; v < m.mNumVertices; ++v)
                target[v] = vec(a->mVertices[v]);
        p.targets.push_back(std::move(target));
        p.target_weights.push_back(a ? double(a->mWeight) : 0.0);
    }
}

// A clip's key times in seconds.
struct ClipSeconds {
    double tps;
    bool gltf;
    // glTF stores key times as float seconds, which assimp turns into float
    // milliseconds, moving a key by up to a microsecond; the nearest float to the
    // time in seconds is the file's own time again.
    double operator()(double ticks) const {
        return gltf ? double(float(ticks / tps)) : ticks / tps;
    }
};

RigData::Channel read_channel(const aiNodeAnim &na, int node,
                              const ClipSeconds &seconds) {
    RigData::Channel ch;
    ch.node = node;
    for (unsigned k = 0; k < na.mNumPositionKeys; ++k)
        ch.position.push_back(
            {seconds(na.mPositionKeys[k].mTime), vec(na.mPositionKeys[k].mValue)});
    for (unsigned k = 0; k < na.mNumRotationKeys; ++k)
        ch.rotation.push_back(
            {seconds(na.mRotationKeys[k].mTime), quat(na.mRotationKeys[k].mValue)});
    for (unsigned k = 0; k < na.mNumScalingKeys; ++k)
        ch.scale.push_back(
            {seconds(na.mScalingKeys[k].mTime), vec(na.mScalingKeys[k].mValue)});
    return ch;
}

RigData::MorphChannel read_morph_channel(const aiMeshMorphAnim &ma, int node,
                                         const ClipSeconds &seconds) {
    RigData::MorphChannel mc;
    mc.node = node;
    for (unsigned k = 0; k < ma.mNumKeys; ++k) {
        const aiMeshMorphKey &key = ma.mKeys[k];
        std::vector<std::pair<uint32_t, double>> w;
        for (unsigned i = 0; i < key.mNumValuesAndWeights; ++i)
            w.push_back({key.mValues[i], key.mWeights[i]});
        mc.keys.push_back({seconds(key.mTime), std::move(w)});
    }
    return mc;
}

// What reading the pieces and clips shares: the file, its nodes by assimp node and by
// name, and the skinned vertices whose weights were scaled to sum to 1.
struct RigReader {
    RigReader(const std::string &path, bool gltf) : path(path), gltf(gltf) {}

    const std::string &path;
    bool gltf;
    std::map<const aiNode *, int> node_index;
    std::map<std::string, int> by_name;
    size_t renormalised = 0;
    double lowest_sum = 1e300, highest_sum = -1e300;

    void read_nodes(const aiNode &root, RigData &d);
    void read_pieces(const aiScene &scene, const sim::assimp_walk::SceneWalk &walk,
                     const std::string &object, RigData &d);
    RigData::Piece read_piece(const aiMesh &m, const sim::assimp_walk::Instance &in);
    void read_skin(const aiMesh &m, const std::string &label, RigData::Piece &p);
    void normalise_weights(const std::vector<std::vector<RigData::Influence>> &per_vertex,
                           const std::string &label, RigData::Piece &p);
    void read_clips(const aiScene &scene, RigData &d, Rig::Clips clips) const;
    RigData::Clip read_clip(const aiAnimation &anim, unsigned a) const;
};

void RigReader::read_nodes(const aiNode &root, RigData &d) {
    add_nodes(root, -1, d, node_index);
    // Bones and channels name their nodes; the first node of a name wins (glTF
    // importers make them unique).
    for (size_t i = 0; i < d.nodes.size(); ++i) by_name.emplace(d.nodes[i].name, int(i));
}

// The pieces, in read_assimp()'s order and with its filter.
void RigReader::read_pieces(const aiScene &scene, const sim::assimp_walk::SceneWalk &walk,
                            const std::string &object, RigData &d) {
    for (const sim::assimp_walk::Instance &in : walk.instances()) {
        const aiMesh &m = *scene.mMeshes[in.mesh];
        if (!(m.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
        RigData::Piece p = read_piece(m, in);
        d.num_vertices += p.vertices.size();
        d.pieces.push_back(std::move(p));
    }
    if (d.pieces.empty())
        throw InputError(
            path, 0, "",
            (object.empty() ? std::string("the file") : "object \"" + object + "\"") +
                " holds no triangles");
}

// The inverse of a transform's linear part (its cofactors over its determinant), the
// identity when it has none: a degenerate node leaves no normals to recover anyway.
Transform linear_inverse(const Transform &x) {
    Transform inv;
    const double det = x.determinant();
    if (!(std::abs(det) > 0) || !std::isfinite(det)) return inv;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
            const int r1 = (r + 1) % 3, r2 = (r + 2) % 3;
            const int c1 = (c + 1) % 3, c2 = (c + 2) % 3;
            inv.a[c][r] = (x.a[r1][c1] * x.a[r2][c2] - x.a[r1][c2] * x.a[r2][c1]) / det;
        }
    return inv;
}

RigData::Piece RigReader::read_piece(const aiMesh &m,
                                     const sim::assimp_walk::Instance &in) {
    const std::string label =
        "mesh " + std::to_string(in.mesh) +
        (m.mName.length > 0 ? " (\"" + name_of(m.mName) + "\")" : std::string());
    RigData::Piece p;
    p.node = node_index.at(in.node);
    p.read_inverse = linear_inverse(in.transform);
    p.vertices.reserve(m.mNumVertices);
    for (unsigned v = 0; v < m.mNumVertices; ++v)
        p.vertices.push_back(vec(m.mVertices[v]));
    read_morph_targets(m, p);
    if (m.mNumBones > 0) read_skin(m, label, p);
    return p;
}

// The skin: each bone's node and inverse bind matrix, each vertex's weights.
void RigReader::read_skin(const aiMesh &m, const std::string &label, RigData::Piece &p) {
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
    normalise_weights(per_vertex, label, p);
}

// Each vertex's influences, scaled to sum to 1, into the piece's flat list.
void RigReader::normalise_weights(
    const std::vector<std::vector<RigData::Influence>> &per_vertex,
    const std::string &label, RigData::Piece &p) {
    p.influence_begin.push_back(0);
    for (size_t v = 0; v < per_vertex.size(); ++v) {
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
                                 ": its bone weights sum to " + std::to_string(sum) +
                                 ", not 1");
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

void RigReader::read_clips(const aiScene &scene, RigData &d, Rig::Clips clips) const {
    for (unsigned a = 0; a < scene.mNumAnimations; ++a) {
        RigData::Clip clip = read_clip(*scene.mAnimations[a], a);
        d.clip_names.push_back(clip.name);
        d.clips.push_back(std::move(clip));
    }
    if (d.clips.empty() && clips == Rig::Clips::required)
        throw InputError(path, 0, "", "the file has no animation clips");
}

// A clip, its keys in seconds.
RigData::Clip RigReader::read_clip(const aiAnimation &anim, unsigned a) const {
    RigData::Clip clip;
    clip.name = name_of(anim.mName);
    if (clip.name.empty()) clip.name = "clip" + std::to_string(a);
    // assimp gives 0 when the file does not say; its own convention is then 25.
    const ClipSeconds seconds{anim.mTicksPerSecond > 0 ? anim.mTicksPerSecond : 25.0,
                              gltf};
    clip.duration = seconds(anim.mDuration);
    auto channel_node = [&](const aiString &name) {
        const auto it = by_name.find(name_of(name));
        if (it == by_name.end())
            throw InputError(path, 0, "",
                             "clip \"" + clip.name + "\" animates \"" + name_of(name) +
                                 "\", which is no node of the file");
        return it->second;
    };
    for (unsigned c = 0; c < anim.mNumChannels; ++c) {
        const aiNodeAnim &na = *anim.mChannels[c];
        clip.channels.push_back(read_channel(na, channel_node(na.mNodeName), seconds));
    }
    for (unsigned c = 0; c < anim.mNumMorphMeshChannels; ++c) {
        const aiMeshMorphAnim &ma = *anim.mMorphMeshChannels[c];
        clip.morphs.push_back(read_morph_channel(ma, channel_node(ma.mName), seconds));
    }
    return clip;
}

// Said once per file and process: every frame reads the rig again.
void note_renormalised(const RigReader &reader) {
    static std::mutex noted_mutex;
    static std::set<std::string> noted;
    const std::lock_guard<std::mutex> lock(noted_mutex);
    if (reader.renormalised > 0 && noted.insert(reader.path).second)
        std::fprintf(stderr,
                     "pelage: %s: the bone weights of %zu vertices summed to %.3g-%.3g; "
                     "scaled to sum to 1 (those without any follow their mesh's node)\n",
                     reader.path.c_str(), reader.renormalised, reader.lowest_sum,
                     reader.highest_sum);
}

}  // namespace

bool Rig::format_has_animation(const std::string &mesh_ref) {
    return has_animation_format(mesh_ref,
                                lower_extension(sim::parse_mesh_spec(mesh_ref).path));
}

Rig Rig::read(const std::string &mesh_ref, Clips clips) {
    const sim::MeshSpec spec = sim::parse_mesh_spec(mesh_ref);
    const std::string &path = spec.path;
    const std::string ext = lower_extension(path);
    check_has_animation(mesh_ref, path, ext);
    Assimp::Importer importer;
    const aiScene &scene = import_scene(importer, path);

    auto d = std::make_unique<RigData>();
    d->path = path;
    RigReader reader{path, ext == "gltf" || ext == "glb"};
    reader.read_nodes(*scene.mRootNode, *d);

    const sim::assimp_walk::SceneWalk walk(scene, spec.object);
    if (!spec.object.empty() && !walk.matched())
        sim::fail_unknown_object(path, spec.object, walk.names());

    reader.read_pieces(scene, walk, spec.object, *d);
    reader.read_clips(scene, *d, clips);
    note_renormalised(reader);
    return Rig(std::move(d));
}

}  // namespace pelage::renderer
