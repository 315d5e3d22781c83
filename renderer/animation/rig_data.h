// The rig's contents (renderer/animation/rig.h), shared by its reader (rig_read.cpp),
// its queries (rig.cpp) and its posing (rig_pose.cpp): plain copies of what assimp
// read, times in seconds.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "sim/mesh/assimp_walk.h"
#include "sim/mesh/mesh.h"

namespace pelage::renderer {

using Transform = sim::assimp_walk::Transform;

struct Quat {
    double w = 1, x = 0, y = 0, z = 0;
};

// A node's local transform as translation, rotation and scale (glTF's TRS; M = T·R·S).
struct Trs {
    sim::Vec3d t{0, 0, 0};
    Quat r;
    sim::Vec3d s{1, 1, 1};
    Transform matrix() const;
};

struct RigData {
    std::string path;  // the file read
    struct Node {
        std::string name;
        int parent = -1;  // parents come before their children
        Transform rest;   // the file's local transform
        Trs rest_trs;     // the same, decomposed: what a channel leaves alone stays
    };
    std::vector<Node> nodes;

    struct Bone {
        int node = -1;
        Transform offset;  // mesh space to the bone's space in the bind pose (IBM)
    };
    struct Influence {
        uint32_t bone;
        double weight;
    };
    // One mesh placed by one node, in the walk's order (sim/mesh/assimp_walk.h).
    struct Piece {
        int node = -1;
        std::vector<sim::Vec3d> vertices;  // mesh space
        std::vector<std::vector<sim::Vec3d>>
            targets;                         // morph targets, absolute positions
        std::vector<double> target_weights;  // their weights without a channel
        std::vector<Bone> bones;             // empty: placed by the node
        // The inverse of the linear part of the node's global transform in the file:
        // normals as read_assimp() gives them (through that transform) back to mesh
        // space, where a pose's map starts.
        Transform read_inverse;
        std::vector<uint32_t> influence_begin;  // per vertex + 1, into influences
        std::vector<Influence> influences;      // weights normalised to sum 1
    };
    std::vector<Piece> pieces;
    size_t num_vertices = 0;

    template <class V>
    struct Key {
        double time;  // seconds
        V value;
    };
    struct Channel {
        int node = -1;
        std::vector<Key<sim::Vec3d>> position, scale;
        std::vector<Key<Quat>> rotation;
    };
    struct MorphChannel {
        int node = -1;  // the node whose meshes' morph weights it sets
        // At each key, (target index, weight) pairs; targets not named keep weight 0.
        std::vector<Key<std::vector<std::pair<uint32_t, double>>>> keys;
    };
    struct Clip {
        std::string name;
        double duration = 0;  // seconds
        std::vector<Channel> channels;
        std::vector<MorphChannel> morphs;
    };
    std::vector<Clip> clips;
    std::vector<std::string> clip_names;
};

}  // namespace pelage::renderer
