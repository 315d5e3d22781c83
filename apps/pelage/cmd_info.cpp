// `pelage info FILE`: what a mesh file holds, before anything is grown on it: its
// objects (the names FILE#NAME selects), each one's and the whole file's triangles,
// vertices, connected components, boundary and non-manifold edges, skin and morph
// targets, and the file's animation clips with their durations. The counts are those of
// the mesh pelage simulates on (coincident vertices welded, zero-area triangles dropped,
// sim/mesh/mesh_clean.h), so a soup of pieces or a torn seam shows here first.
#include <fmt/core.h>

#include <algorithm>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "apps/common/common.h"
#include "renderer/animation/rig.h"
#include "sim/mesh/mesh_load.h"
#include "sim/mesh/topology.h"

namespace pelage::renderer::cli {
namespace {

struct InfoOptions {
    std::string file;
    bool json = false;
};

// Reading each object reads the file again: past this many, the rest are named only.
constexpr size_t max_detailed_objects = 64;

struct MeshCounts {
    std::string name;  // the object's name, "" for the whole file
    size_t triangles = 0, vertices = 0, components = 0, boundary_edges = 0,
           nonmanifold_edges = 0;
    std::optional<size_t> bones, morph_targets;  // none: a format without rigs
};

// The counts of one mesh reference; `read` gets the file's object names.
MeshCounts count_mesh(const std::string &ref, sim::MeshReadStats *read) {
    sim::MeshCleanStats clean;
    sim::TriangleMesh mesh;
    if (ref.rfind("procedural:", 0) == 0) {
        sim::MeshLoadReport report;
        mesh = sim::load_mesh(ref, &report);
        clean = report.clean;
    } else {
        // read_mesh, not load_mesh: listing the file is no reason to say it was merged.
        const sim::MeshSpec spec = sim::parse_mesh_spec(ref);
        mesh = sim::clean_mesh(sim::read_mesh(spec.path, read, spec.object), ref, {},
                               &clean);
    }
    const sim::Topology topo = sim::build_topology(mesh);
    MeshCounts c;
    c.triangles = mesh.num_triangles();
    c.vertices = mesh.num_vertices() - clean.unused_vertices;
    c.components = topo.num_components;
    c.boundary_edges = topo.boundary_edges;
    c.nonmanifold_edges = topo.nonmanifold_edges;
    if (Rig::format_has_animation(ref)) {
        const Rig rig = Rig::read(ref, Rig::Clips::optional);
        c.bones = rig.num_bones();
        c.morph_targets = rig.num_morph_targets();
    }
    return c;
}

struct Clip {
    std::string name;
    double seconds;
};

struct FileInfo {
    std::string file;
    std::vector<MeshCounts> objects;  // the first max_detailed_objects
    std::vector<std::string> more;    // the names past them
    MeshCounts total;
    std::vector<Clip> clips;
};

FileInfo read_info(const std::string &ref) {
    FileInfo info;
    info.file = ref;
    sim::MeshReadStats read;
    info.total = count_mesh(ref, &read);
    const bool one_object =
        ref.rfind("procedural:", 0) != 0 && !sim::parse_mesh_spec(ref).object.empty();
    if (!one_object) {
        const std::vector<std::string> names = sim::unique_names(read.object_names);
        for (const std::string &name : names) {
            if (info.objects.size() == max_detailed_objects) {
                info.more.push_back(name);
                continue;
            }
            info.objects.push_back(count_mesh(ref + "#" + name, nullptr));
            info.objects.back().name = name;
        }
    }
    if (Rig::format_has_animation(ref)) {
        const Rig rig = Rig::read(ref, Rig::Clips::optional);
        for (size_t i = 0; i < rig.clip_names().size(); ++i)
            info.clips.push_back({rig.clip_names()[i], rig.duration_seconds(int(i))});
    }
    return info;
}

nlohmann::json counts_json(const MeshCounts &c) {
    nlohmann::json j = {{"triangles", c.triangles},
                        {"vertices", c.vertices},
                        {"components", c.components},
                        {"boundary_edges", c.boundary_edges},
                        {"nonmanifold_edges", c.nonmanifold_edges}};
    if (c.bones) {
        j["skinned"] = *c.bones > 0;
        j["bones"] = *c.bones;
        j["morph_targets"] = *c.morph_targets;
    }
    return j;
}

void print_json(const FileInfo &info) {
    nlohmann::json j = {{"file", info.file},
                        {"objects", nlohmann::json::array()},
                        {"more_objects", info.more},
                        {"total", counts_json(info.total)},
                        {"clips", nlohmann::json::array()}};
    for (const MeshCounts &c : info.objects) {
        nlohmann::json o = counts_json(c);
        o["name"] = c.name;
        o["reference"] = info.file + "#" + c.name;
        j["objects"].push_back(o);
    }
    for (const Clip &c : info.clips)
        j["clips"].push_back({{"name", c.name}, {"seconds", c.seconds}});
    std::cout << j.dump(2) << std::endl;
}

std::string rig_text(const MeshCounts &c) {
    if (!c.bones) return "";
    auto count = [](size_t n, const char *what) {
        return fmt::format("{} {}{}", n, what, n == 1 ? "" : "s");
    };
    std::string s = *c.bones > 0 ? "skinned, " + count(*c.bones, "bone") : "";
    if (*c.morph_targets > 0)
        s += (s.empty() ? "" : "; ") + count(*c.morph_targets, "morph target");
    return s.empty() ? "-" : s;
}

void print_text(const FileInfo &info) {
    size_t width = std::string("whole file").size();
    for (const MeshCounts &c : info.objects) width = std::max(width, c.name.size());
    // The skin column only for a format that carries one.
    const bool rigged = info.total.bones.has_value();
    auto row = [&](const std::string &name, const MeshCounts &c) {
        fmt::print("  {:<{}} {:>10} {:>10} {:>10} {:>14} {:>18}{}\n", name, width,
                   c.triangles, c.vertices, c.components, c.boundary_edges,
                   c.nonmanifold_edges, rigged ? "  " + rig_text(c) : "");
    };
    fmt::print("{}\n", info.file);
    fmt::print("  {:<{}} {:>10} {:>10} {:>10} {:>14} {:>18}{}\n", "object", width,
               "triangles", "vertices", "components", "boundary edges",
               "non-manifold edges", rigged ? "  skin, morph targets" : "");
    for (const MeshCounts &c : info.objects) row(c.name, c);
    row(info.objects.empty() ? "the mesh" : "whole file", info.total);
    if (!info.more.empty()) {
        std::string list;
        for (const std::string &n : info.more) list += (list.empty() ? "" : ", ") + n;
        fmt::print("  and {} more objects: {}\n", info.more.size(), list);
    }
    if (!info.objects.empty())
        fmt::print("  (select an object with {}#NAME)\n", info.file);
    if (info.clips.empty()) {
        if (rigged) fmt::print("  no animation clips\n");
        return;
    }
    fmt::print("  clips (look --clip NAME):\n");
    for (const Clip &c : info.clips) fmt::print("    {}  {:.4g} s\n", c.name, c.seconds);
}

int run(const InfoOptions &o) {
    const FileInfo info = read_info(o.file);
    if (o.json)
        print_json(info);
    else
        print_text(info);
    return 0;
}

}  // namespace

Runner add_info_command(CLI::App &app) {
    auto o = std::make_shared<InfoOptions>();
    CLI::App *sub = app.add_subcommand(
        "info",
        "List a mesh file's objects, their triangles, components and open or "
        "non-manifold edges, skins, morph targets and animation clips");
    sub->add_option("file", o->file,
                    "Mesh file (OFF, OBJ, PLY, glTF, FBX, ...), FILE#NAME for one object "
                    "of it, or procedural:...")
        ->required();
    sub->add_flag("--json", o->json, "Print JSON instead of text");
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
