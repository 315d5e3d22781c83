// clonal_mosaic: the pattern of a `pelage sim` run, looked up at every hit by the
// closest-cell search of Teo 2006 ch. 6 (closest_cell.h).
//
// The parameters and AOVs are the tables below (`pelage shaders clonal_mosaic` prints
// them). The object needs "cells": a .cells file made by `pelage sim` for the same mesh
// (checked against the mesh's hash). Albedo is the cell type's colour; eumelanin and
// pheomelanin are passed on for the fur.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "pattern/mosaic/coherent_lookup.h"
#include "pattern/mosaic/mosaic_lod.h"
#include "pattern/mosaic/pattern.h"
#include "shader/clonal_mosaic/pattern_cache.h"
#include "shader/pelage_shader.h"
#include "shader/sdk/create_guard.h"
#include "shader/sdk/params.h"
#include "shader/sdk/rest_mesh.h"

namespace {

using namespace pelage;

// A cell type's look: its colour, melanins, and the coat overrides (< 0 / 0: the
// material's).
struct TypeLook {
    float colour[3];
    float eumelanin, pheomelanin;
    float roughness;  // < 0: the material's
    float ior;        // 0: the material's
    float aov_type;
};

// A cell's look, resolved when the instance is created (type colour, jitter, clamp): the
// hit path reads one entry and its type's, instead of hashing the id and scaling the
// colour.
struct CellLook {
    float rgb[3];
    uint32_t type;
    float aov_id;
    uint32_t id;       // the stable cell id (the "cell" matte)
    uint32_t founder;  // the founder of its clone (the "lineage" matte)
};

struct ClonalMosaic {
    // Shared by every instance of this file on this mesh (pattern_cache.h).
    std::shared_ptr<const pattern::mosaic::MosaicPattern> pattern;
    const pattern::mosaic::CellTable *cells_ptr = nullptr;
    const pattern::mosaic::ClosestCellIndex *index = nullptr;
    // Rendering another mesh of the simulation surface's shape: hits are carried onto it
    // (surface_transfer.h); null when the render mesh is the simulation's own.
    const pattern::transfer::SurfaceTransfer *transfer = nullptr;
    // Simulation triangles that reach no cell (pieces of a triangle soup) carried to the
    // closest cell-bearing surface (cell_cover.h); null when there are none.
    const pattern::transfer::CellCover *cover = nullptr;
    std::vector<TypeLook> types;
    std::vector<CellLook> looks;                      // per cell, CellTable order
    std::unique_ptr<pattern::mosaic::MosaicLod> lod;  // null: lod = 0
    float jitter = 0, edge_width = 0;
    bool antialias = true, coherence = true;
    // shade()'s fast path for camera hits: their footprints up to this width see the
    // exact pattern on every triangle (no level of detail); < 0: no fast path (coherence
    // or antialiasing off).
    float camera_reuse_up_to = -1;
    uint32_t num_triangles = 0;
    uint64_t serial = 0;      // this instance among all ever created (never 0)
    std::string object_name;  // names the cells' mattes
    uint32_t matte_bits = 0;  // the matte layers this instance fills
};

std::atomic<uint64_t> instances_created{0};

// Consecutive camera hits of a thread mostly fall in the same cell: reuse it when that
// is provably right (coherent_lookup.h; identical results either way).
// Initial-exec TLS: each access is one %fs-relative address instead of a TLS descriptor
// call (two per camera hit). A dlopen()ed module may use it for a few bytes: glibc keeps
// a static TLS surplus for them (rtld.optional_static_tls, 512 bytes by default; this
// object is ~100), and loading fails cleanly, not silently, if it ever ran out.
[[gnu::tls_model(
    "initial-exec")]] thread_local pattern::mosaic::CoherentLookup coherent_lookup;

const PelageParamSpec params[] = {
    {"jitter",
     PELAGE_PARAM_FLOAT,
     {0, 0, 0},
     nullptr,
     0.0f,
     1.0f,
     "per-cell brightness variation, keyed by the stable cell id"},
    {"edge_width",
     PELAGE_PARAM_FLOAT,
     {0, 0, 0},
     nullptr,
     0.0f,
     1e6f,
     "soft boundary between cells, in object-space units"},
    {"antialias",
     PELAGE_PARAM_INT,
     {1, 0, 0},
     nullptr,
     0.0f,
     1.0f,
     "blend cell boundaries over the ray footprint"},
    {"roughness",
     PELAGE_PARAM_STRING,
     {0, 0, 0},
     "",
     0.0f,
     0.0f,
     "per-type coat roughness, e.g. \"F=0.35,B=0.5\"; empty keeps the material's"},
    {"specular",
     PELAGE_PARAM_STRING,
     {0, 0, 0},
     "",
     0.0f,
     0.0f,
     "per-type coat reflectance at normal incidence (F0, 0…0.25; 0.04 = ior 1.5), e.g. "
     "\"F=0.02,B=0.05\"; empty keeps the material's ior"},
    {"types",
     PELAGE_PARAM_STRING,
     {0, 0, 0},
     "",
     0.0f,
     0.0f,
     "per-type look without simulating again, as a JSON object: {\"F\": {\"colour\": "
     "[r, g, b], \"eumelanin\": e, \"pheomelanin\": p, \"roughness\": r, "
     "\"specular\": f0}}; each key optional"},
    {"neighbourhood",
     PELAGE_PARAM_STRING,
     {0, 0, 0},
     "geodesic",
     0.0f,
     0.0f,
     "\"geodesic\" (exact surface distances), or the planar unfoldings kept to compare "
     "with: \"edges\" (edge maps) or \"teo\" (edge and vertex maps, Teo 2006)"},
    {"lod",
     PELAGE_PARAM_INT,
     {1, 0, 0},
     nullptr,
     0.0f,
     1.0f,
     "footprints wider than the triangles see the cells' mean look (0: point-sample "
     "the cells at every depth)"},
    {"coherence",
     PELAGE_PARAM_INT,
     {1, 0, 0},
     nullptr,
     0.0f,
     1.0f,
     "reuse the previous hit's cell when it is provably the same (same image; 0 to time "
     "without)"},
    {nullptr, PelageParamType(0), {0, 0, 0}, nullptr, 0, 0, nullptr},
};

const char *const aov_names[] = {"cell_id", "cell_type", "f1", nullptr};
// Cryptomatte layers: a cell type is one matte across objects (its name); a cell is
// "<object>/cell <id>"; a clone, every descendant of one initial cell whatever its
// type, is "<object>/clone <founder id>" (files from before lineage have none).
enum MatteLayer : uint32_t { matte_type = 0, matte_cell = 1, matte_lineage = 2 };
const char *const matte_names[] = {"type", "cell", "lineage", nullptr};

// "F=0.35,B=0.5" -> one value per named type, each in [lo, hi], handed to `set`; throws
// std::invalid_argument naming the parameter and the problem.
template <typename Set>
void parse_per_type(const char *param, const std::string &spec, float lo, float hi,
                    const std::vector<sim::CellsFileType> &types, Set set) {
    std::stringstream ss(spec);
    std::string item;
    while (std::getline(ss, item, ',')) {
        if (item.empty()) continue;
        const size_t eq = item.find('=');
        if (eq == std::string::npos)
            throw std::invalid_argument(std::string(param) +
                                        ": expected NAME=VALUE, got \"" + item + "\"");
        const std::string name = item.substr(0, eq);
        auto it = std::find_if(types.begin(), types.end(),
                               [&](const auto &t) { return t.name == name; });
        if (it == types.end())
            throw std::invalid_argument(std::string(param) +
                                        ": the .cells file has no cell type \"" + name +
                                        "\"");
        char *end = nullptr;
        const std::string value = item.substr(eq + 1);
        const float v = std::strtof(value.c_str(), &end);
        if (value.empty() || *end || !(v >= lo && v <= hi)) {
            std::ostringstream range;
            range << "[" << lo << ", " << hi << "]";
            throw std::invalid_argument(std::string(param) + ": \"" + value + "\" for " +
                                        name + " is not in " + range.str());
        }
        set(size_t(it - types.begin()), v);
    }
}

// F0 = ((η - 1) / (η + 1))², so η = (1 + √F0) / (1 - √F0): F0 0.25 is η = 3.
float ior_of_f0(float f0) {
    const float r = std::sqrt(f0);
    return std::min((1 + r) / (1 - r), 3.0f);
}

// The "types" parameter: each named type's look replaced, key by key. Throws
// std::invalid_argument naming the field ("types.F.colour[1]") and the problem.
void apply_type_looks(const std::string &text,
                      const std::vector<sim::CellsFileType> &types,
                      std::vector<TypeLook> &looks, std::vector<bool> &set_roughness,
                      std::vector<bool> &set_specular) {
    if (text.empty()) return;
    const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
    if (!j.is_object())
        throw std::invalid_argument(
            "types: expected an object such as {\"F\": {\"colour\": [0.1, 0.05, "
            "0.02]}}");
    for (const auto &[name, look] : j.items()) {
        const std::string at = "types." + name;
        auto it = std::find_if(types.begin(), types.end(),
                               [&](const auto &t) { return t.name == name; });
        if (it == types.end()) {
            std::string all;
            for (const auto &t : types) all += (all.empty() ? "" : ", ") + t.name;
            throw std::invalid_argument(at + ": the .cells file has no cell type \"" +
                                        name + "\" (it has " + all + ")");
        }
        if (!look.is_object())
            throw std::invalid_argument(at +
                                        ": expected an object of colour, eumelanin, "
                                        "pheomelanin, roughness, specular");
        TypeLook &t = looks[size_t(it - types.begin())];
        const size_t k = size_t(it - types.begin());
        auto number = [&](const nlohmann::json &v, const std::string &field, float lo,
                          float hi) {
            if (!v.is_number() || !(v.get<double>() >= lo && v.get<double>() <= hi))
                throw std::invalid_argument(field + ": " + v.dump() +
                                            " is not a number in [" +
                                            std::to_string(lo).substr(0, 4) + ", " +
                                            std::to_string(hi).substr(0, 4) + "]");
            return v.get<float>();
        };
        for (const auto &[key, v] : look.items()) {
            const std::string f = at + "." + key;
            if (key == "colour" || key == "color") {
                if (look.contains("colour") && look.contains("color"))
                    throw std::invalid_argument(at +
                                                ": give \"colour\" or \"color\", "
                                                "not both");
                if (!v.is_array() || v.size() != 3)
                    throw std::invalid_argument(f + ": expected [r, g, b] (linear)");
                for (int c = 0; c < 3; ++c)
                    t.colour[c] =
                        number(v[size_t(c)], f + "[" + std::to_string(c) + "]", 0, 1);
            } else if (key == "eumelanin") {
                t.eumelanin = number(v, f, 0, 50);
            } else if (key == "pheomelanin") {
                t.pheomelanin = number(v, f, 0, 50);
            } else if (key == "roughness") {
                if (set_roughness[k])
                    throw std::invalid_argument(f +
                                                ": the \"roughness\" parameter "
                                                "already sets " +
                                                name);
                t.roughness = number(v, f, 0, 1);
            } else if (key == "specular") {
                if (set_specular[k])
                    throw std::invalid_argument(f +
                                                ": the \"specular\" parameter "
                                                "already sets " +
                                                name);
                t.ior = ior_of_f0(number(v, f, 0, 0.25f));
            } else {
                throw std::invalid_argument(f +
                                            ": unknown key (expected colour, "
                                            "eumelanin, pheomelanin, roughness, "
                                            "specular)");
            }
        }
    }
}

// A stable value in [-1, 1] from a cell id (integer hash, no state). Not mix64
// (sim/core/hash.h): its value scales every cell's colour, so it stays bit-identical to
// keep rendered pixels, and the shared 64-bit mixer gives other values.
float id_noise(uint32_t id) {
    uint32_t h = id * 0x9E3779B1u;
    h ^= h >> 16;
    h *= 0x85EBCA6Bu;
    h ^= h >> 13;
    return float(h >> 8) * (2.0f / 16777216.0f) - 1.0f;
}

// A stable value in [0, 1) from a hit (its triangle, barycentrics and depth): decides,
// between the exact and the filtered look, which one a hit in the level of detail's ramp
// takes (murmur3's finaliser on the mixed bits). Not mix64 (sim/core/hash.h): its value
// picks the look a hit shows, so it stays bit-identical to keep rendered pixels.
float hit_noise(const PelageHit &hit) {
    uint32_t b1, b2;
    std::memcpy(&b1, &hit.b1, 4);
    std::memcpy(&b2, &hit.b2, 4);
    uint32_t h = hit.primitive_id * 0x9E3779B1u ^ b1 * 0x85EBCA6Bu ^ b2 * 0xC2B2AE35u ^
                 hit.depth * 0x27D4EB2Fu;
    h ^= h >> 16;
    h *= 0x85EBCA6Bu;
    h ^= h >> 13;
    h *= 0xC2B2AE35u;
    h ^= h >> 16;
    return float(h >> 8) * (1.0f / 16777216.0f);
}

void cell_look(const ClonalMosaic &cm, uint32_t cell, CellLook &look) {
    const uint32_t type = cm.cells_ptr->type[cell];
    const TypeLook &t = cm.types[type];
    const float scale = 1.0f + cm.jitter * 0.5f * id_noise(cm.cells_ptr->id[cell]);
    for (int c = 0; c < 3; ++c) look.rgb[c] = std::clamp(t.colour[c] * scale, 0.0f, 1.0f);
    look.type = type;
    look.aov_id = float(cm.cells_ptr->id[cell]);  // exact below 2^24 cells
    look.id = cm.cells_ptr->id[cell];
    look.founder = look.id;
}

// Pieces of the surface with no cell of their own are shown the closest cells
// (cell_cover.h); the user is told when that is a visible part of the object: over 1 %
// of its area, or over 0.1 % in a hundred pieces or more (a triangle soup, whose legs
// would otherwise be patchworks of borrowed cells). A clean animal's eyes or claws, a
// few small parts, stay quiet. No cells anywhere is always said.
void warn_uncovered(const pattern::transfer::CellCoverReport &r, const char *cells_path,
                    const std::string &mesh_name, const PelageParamSet &ps) {
    char message[1024];
    if (r.without_cell_share > 0) {
        std::snprintf(message, sizeof message,
                      "clonal_mosaic: %s holds no cell that any triangle of %s reaches: "
                      "the object renders in the material's colour (shader.cell_id -1); "
                      "grow it again with more cells (pelage sim --initial-cells)",
                      cells_path, mesh_name.c_str());
        ps.warn(ps.warn_context, message);
        return;
    }
    constexpr size_t soup_pieces = 100;
    const bool soup = r.carried_pieces >= soup_pieces;
    if (!(r.carried_area_share > 0.01 || (soup && r.carried_area_share > 1e-3))) return;
    std::snprintf(
        message, sizeof message,
        "clonal_mosaic: %.2f %% of the area of %s (%zu of its %zu pieces, %zu triangles) "
        "holds no cell of its own and shows the cells of the closest surface that does, "
        "up to %.2f %% of the mesh's size away; %s",
        100 * r.carried_area_share, mesh_name.c_str(), r.carried_pieces, r.pieces,
        r.carried_triangles, 100 * r.max_carry_distance,
        soup ? "the mesh looks like a triangle soup: weld it (Blender: Mesh > Clean Up > "
               "Merge by Distance) and grow the cells again for a pattern that runs "
               "across the pieces"
             : "those pieces are smaller than the cells: give them a material of their "
               "own, or grow more cells (pelage sim --initial-cells)");
    ps.warn(ps.warn_context, message);
}

std::unique_ptr<ClonalMosaic> make(const PelageParamSet &ps) {
    if (!ps.mesh.cells_path)
        throw std::invalid_argument(
            "needs the object's \"cells\": a .cells file made by pelage sim");
    if (!ps.mesh.rest_positions || !ps.mesh.triangles)
        throw std::invalid_argument("the renderer gave no mesh");
    const shader::sdk::Params p(params, ps);
    auto cm = std::make_unique<ClonalMosaic>();
    cm->jitter = p.get_float("jitter");
    cm->edge_width = p.get_float("edge_width");
    cm->antialias = p.get_bool("antialias");
    cm->coherence = p.get_bool("coherence");
    cm->serial = ++instances_created;
    cm->object_name = ps.object_name ? ps.object_name : "";
    const std::string neighbourhood = p.get_string("neighbourhood");
    if (neighbourhood != "geodesic" && neighbourhood != "edges" && neighbourhood != "teo")
        throw std::invalid_argument("neighbourhood: \"" + neighbourhood +
                                    "\" is none of \"geodesic\", \"edges\", \"teo\"");

    const std::string mesh_name = ps.mesh.mesh_name ? ps.mesh.mesh_name : "the mesh";
    cm->pattern = shader::clonal_mosaic::cached_pattern(
        ps.mesh.cells_path, shader::sdk::rest_mesh(ps.mesh, false), mesh_name,
        neighbourhood == "geodesic" ? pattern::mosaic::Neighbourhood::geodesic
        : neighbourhood == "teo"    ? pattern::mosaic::Neighbourhood::unfolding_teo
                                    : pattern::mosaic::Neighbourhood::unfolding_edges);
    cm->transfer = cm->pattern->transfer();
    // `pelage sim` grows a mesh far from the cells' scale on its own copy of it, split
    // at its edge midpoints or simplified (sim/remesh/cell_scale_surface.h), and the
    // file records which (params "simulation_surface"). The note names that copy as
    // pelage's own: "triangulated otherwise" or "another mesh" read as a mismatch of
    // the user's files when the Fox or the cow is rendered on the mesh it was grown
    // from. A pattern grown on another mesh is named as such.
    enum class Copy { none, split, simplified };
    const auto own_copy = [&] {
        const nlohmann::json j =
            nlohmann::json::parse(cm->pattern->data().params_json, nullptr, false);
        if (!j.is_object() || !j.contains("simulation_surface")) return Copy::none;
        const nlohmann::json &sf = j["simulation_surface"];
        if (!sf.is_object()) return Copy::none;
        const auto field = [&](const char *k) {
            return sf.contains(k) ? sf[k] : nlohmann::json();
        };
        const nlohmann::json simplified = field("simplified"),
                             levels = field("refine_levels"),
                             input = field("input_triangles");
        if (!input.is_number_unsigned() ||
            input.get<uint64_t>() != cm->transfer->num_render_triangles())
            return Copy::none;
        if (simplified.is_boolean() && simplified.get<bool>()) return Copy::simplified;
        if (levels.is_number_unsigned() && levels.get<uint64_t>() > 0) return Copy::split;
        return Copy::none;
    };
    if (cm->transfer) {
        char message[1024];
        const bool same_surface =
            !cm->transfer->similarity_applied() && cm->transfer->max_deviation() < 1e-6;
        const Copy copy = own_copy();
        if (copy == Copy::split && same_surface)
            std::snprintf(
                message, sizeof message,
                "clonal_mosaic: %s was grown on pelage sim's copy of %s split at "
                "its edge midpoints (%zu triangles, here %zu): the same surface, "
                "every point in its own cell",
                ps.mesh.cells_path, mesh_name.c_str(), cm->pattern->num_triangles(),
                cm->transfer->num_render_triangles());
        else if (copy == Copy::simplified && !cm->transfer->similarity_applied())
            std::snprintf(
                message, sizeof message,
                "clonal_mosaic: %s was grown on pelage sim's simplified copy of %s "
                "(%zu triangles, here %zu) and is rendered through the closest "
                "points of that copy, at most %.2g %% of the mesh's size away",
                ps.mesh.cells_path, mesh_name.c_str(), cm->pattern->num_triangles(),
                cm->transfer->num_render_triangles(),
                100 * cm->transfer->max_deviation());
        else if (same_surface)
            std::snprintf(message, sizeof message,
                          "clonal_mosaic: %s was grown on %s triangulated otherwise (%zu "
                          "triangles, here %zu): the same surface, every point in its "
                          "own cell",
                          ps.mesh.cells_path, mesh_name.c_str(),
                          cm->pattern->num_triangles(),
                          cm->transfer->num_render_triangles());
        else
            std::snprintf(
                message, sizeof message,
                "clonal_mosaic: %s was grown on another mesh of this shape (%zu "
                "triangles%s); it is rendered on %s (%zu triangles) through the "
                "closest points of that surface, at most %.2g %% of its size away",
                ps.mesh.cells_path, cm->pattern->num_triangles(),
                cm->transfer->similarity_applied() ? ", another size or place" : "",
                mesh_name.c_str(), cm->transfer->num_render_triangles(),
                100 * cm->transfer->max_deviation());
        ps.warn(ps.warn_context, message);
    }
    warn_uncovered(cm->pattern->cover().report(), ps.mesh.cells_path, mesh_name, ps);
    if (cm->pattern->cover().active()) cm->cover = &cm->pattern->cover();
    const size_t render_triangles = cm->transfer ? cm->transfer->num_render_triangles()
                                                 : cm->pattern->num_triangles();
    if (render_triangles != ps.mesh.num_triangles)
        throw std::invalid_argument(
            "the renderer's mesh has " + std::to_string(ps.mesh.num_triangles) +
            " triangles, the pattern's " + std::to_string(render_triangles));
    cm->cells_ptr = &cm->pattern->cells();
    cm->index = &cm->pattern->index();
    const std::vector<sim::CellsFileType> &types = cm->pattern->types();
    for (size_t k = 0; k < types.size(); ++k) {
        const sim::CellsFileType &t = types[k];
        cm->types.push_back({{t.colour[0], t.colour[1], t.colour[2]},
                             t.eumelanin,
                             t.pheomelanin,
                             -1.0f,
                             0.0f,
                             float(k)});
    }
    std::vector<bool> set_roughness(types.size()), set_specular(types.size());
    parse_per_type("roughness", p.get_string("roughness"), 0, 1, types,
                   [&](size_t k, float r) {
                       cm->types[k].roughness = r;
                       set_roughness[k] = true;
                   });
    parse_per_type("specular", p.get_string("specular"), 0, 0.25f, types,
                   [&](size_t k, float f0) {
                       cm->types[k].ior = ior_of_f0(f0);
                       set_specular[k] = true;
                   });
    apply_type_looks(p.get_string("types"), types, cm->types, set_roughness,
                     set_specular);
    cm->looks.resize(cm->cells_ptr->size());
    for (uint32_t k = 0; k < cm->looks.size(); ++k) cell_look(*cm, k, cm->looks[k]);
    cm->matte_bits = 1u << matte_type | 1u << matte_cell;
    if (const sim::CellsData &d = cm->pattern->data(); !d.founder.empty()) {
        // Ids are dense (cells are never destroyed): the file's founders by id.
        std::vector<uint32_t> founder_of(d.id.size(), 0);
        for (size_t k = 0; k < d.id.size(); ++k)
            if (d.id[k] < founder_of.size()) founder_of[d.id[k]] = d.founder[k];
        for (CellLook &look : cm->looks)
            if (look.id < founder_of.size()) look.founder = founder_of[look.id];
        cm->matte_bits |= 1u << matte_lineage;
    }
    if (p.get_bool("lod"))
        cm->lod = std::make_unique<pattern::mosaic::MosaicLod>(
            *cm->pattern,
            [&](uint32_t cell) {
                const CellLook &look = cm->looks[cell];
                const TypeLook &type = cm->types[look.type];
                return pattern::mosaic::FilteredLook{{look.rgb[0], look.rgb[1],
                                                      look.rgb[2], type.eumelanin,
                                                      type.pheomelanin}};
            },
            cm->types.size());
    cm->num_triangles = uint32_t(cm->cells_ptr->num_triangles());
    if (cm->coherence && cm->antialias)
        cm->camera_reuse_up_to =
            cm->lod ? cm->lod->exact_up_to() : std::numeric_limits<float>::infinity();
    return cm;
}

// The hit takes the look of one cell.
void shade_as(const ClonalMosaic &cm, const CellLook &cell, float f1, PelageShade *out) {
    const TypeLook &type = cm.types[cell.type];
    for (int k = 0; k < 3; ++k) out->albedo[k] = cell.rgb[k];
    out->eumelanin = type.eumelanin;
    out->pheomelanin = type.pheomelanin;
    // Unconditionally: a type without an override holds the ABI's "keep the material's"
    // values (roughness < 0, ior 0), so no branch is needed.
    out->roughness = type.roughness;
    out->ior = type.ior;
    out->aov[0] = cell.aov_id;
    out->aov[1] = type.aov_type;
    out->aov[2] = f1;
    out->aov_written = 1;
    out->cell_type = int32_t(cell.type);
    out->matte[matte_type] = cell.type;
    out->matte[matte_cell] = cell.id;
    out->matte[matte_lineage] = cell.founder;
    out->matte_written = cm.matte_bits;
}

// Blend the (up to) three nearest cells of n, nearest first, with weights
// 1 - smoothstep(0, 2w, F_i - F1): equal on a Voronoi edge (F1 = F2) and at a vertex
// (F1 = F2 = F3), zero once a cell is 2w farther than the nearest. Continuous everywhere
// except where four cells lie within 2w of each other's distance.
inline void shade_blend(const ClonalMosaic &cm,
                        const pattern::mosaic::CoherentLookup::Result &n, float w,
                        PelageShade *out) {
    const float f1 = std::sqrt(n.d2[0]);
    const CellLook &nearest = cm.looks[n.index[0]];
    // No other cell within 2w (most hits): the blend is the nearest cell's look exactly
    // (weight 1, total 1), so skip the arithmetic.
    if (n.index[1] == pattern::mosaic::ClosestCell::none) {
        shade_as(cm, nearest, f1, out);
        return;
    }
    // Multiplications by reciprocals, not divisions: a fair share of camera hits blend,
    // and a division costs several multiplications.
    // (A width below the least normal float would make the reciprocal infinite, and the
    // nearest cell's 0 · inf a NaN.)
    const float inv_width = 1 / std::max(2 * w, std::numeric_limits<float>::min());
    float rgb[3] = {0, 0, 0}, eu = 0, pheo = 0, total = 0;
    for (int i = 0; i < 3 && n.index[i] != pattern::mosaic::ClosestCell::none; ++i) {
        const float x = std::min((std::sqrt(n.d2[i]) - f1) * inv_width, 1.0f);
        const float weight = 1 - x * x * (3 - 2 * x);
        if (weight <= 0) break;
        const CellLook &cell = cm.looks[n.index[i]];
        const TypeLook &type = cm.types[cell.type];
        for (int k = 0; k < 3; ++k) rgb[k] += weight * cell.rgb[k];
        eu += weight * type.eumelanin;
        pheo += weight * type.pheomelanin;
        total += weight;
    }
    shade_as(cm, nearest, f1, out);
    const float inv_total = 1 / total;  // total >= 1: the nearest cell's weight is 1
    for (int k = 0; k < 3; ++k) out->albedo[k] = rgb[k] * inv_total;
    out->eumelanin = eu * inv_total;
    out->pheomelanin = pheo * inv_total;
}

// The pattern itself at the hit: one cell's look, or a blend across a boundary.
// `tried`: this thread's CoherentLookup when shade()'s fast path already found its
// reuse impossible (null otherwise).
void shade_cells(const ClonalMosaic &cm, const PelageHit *hit, PelageShade *out,
                 pattern::mosaic::CoherentLookup *tried) {
    // Boundaries are blended over w: the user's soft width, or at least the footprint.
    // Antialiasing matters for what the camera sees; indirect bounces average over wide
    // footprints anyway, so they take the cheaper nearest-cell path.
    const float w =
        std::max(cm.edge_width, cm.antialias && hit->depth == 0 ? hit->footprint : 0.0f);
    if (w <= 0) {
        const pattern::mosaic::ClosestCell c =
            cm.index->find_nearest(hit->primitive_id, hit->b1, hit->b2);
        if (c.index == pattern::mosaic::ClosestCell::none)
            return;  // a component without cells
        shade_as(cm, cm.looks[c.index], c.f1, out);
        return;
    }
    // One search finds the cells to blend: it stops at F1 + 2w, so hits far from any
    // boundary cost little more than the nearest cell alone.
    const float band = 2 * w;
    const uint32_t t = hit->primitive_id;
    const auto n = !cm.coherence ? cm.index->find_three_within(t, hit->b1, hit->b2, band)
                   : tried
                       ? tried->search(*cm.index, cm.serial, t, hit->b1, hit->b2, band)
                       : coherent_lookup.find_three_within(*cm.index, cm.serial, t,
                                                           hit->b1, hit->b2, band);
    if (n.index[0] == pattern::mosaic::ClosestCell::none) return;
    shade_blend(cm, n, w, out);
}

// Footprints wider than the triangles: the cells' mean look (mosaic_lod.h), faded in
// over footprints of one to two triangle sizes. In the ramp a hit takes one of the two
// looks, the filtered one with probability equal to its weight (stochastic filtering,
// Pharr et al. 2024, "Filtering after shading with stochastic texture filtering"): the
// same mean over a pixel's samples as blending both, at the cost of one.
//
// Every hit but the camera's reused ones goes through shade_any(), out of line, so the
// path most calls take stays short: a reused single-cell hit runs without a stack
// frame and with few instructions.
[[gnu::noinline]] void shade_any(const ClonalMosaic &cm, const PelageHit *hit,
                                 PelageShade *out,
                                 pattern::mosaic::CoherentLookup *tried) {
    const uint32_t t = hit->primitive_id;
    if (t >= cm.num_triangles) return;  // defaults stay
    const float weight = cm.lod ? cm.lod->weight(t, hit->footprint) : 0.0f;
    if (weight < 1 && !(weight > 0 && hit_noise(*hit) < weight)) {
        shade_cells(cm, hit, out, tried);
    } else {
        // The filtered look. No single cell is seen, so roughness and ior come from the
        // triangle's dominant type; the camera's AOVs still name the nearest cell.
        const TypeLook &type = cm.types[cm.lod->dominant_type(t)];
        if (type.roughness >= 0) out->roughness = type.roughness;
        if (type.ior > 0) out->ior = type.ior;
        if (hit->depth == 0) {
            const pattern::mosaic::ClosestCell c =
                cm.index->find_nearest(t, hit->b1, hit->b2);
            if (c.index != pattern::mosaic::ClosestCell::none) {
                const CellLook &cell = cm.looks[c.index];
                out->aov[0] = cell.aov_id;
                out->aov[1] = cm.types[cell.type].aov_type;
                out->aov[2] = c.f1;
                out->aov_written = 1;
                out->cell_type = int32_t(cell.type);
                out->matte[matte_type] = cell.type;
                out->matte[matte_cell] = cell.id;
                out->matte[matte_lineage] = cell.founder;
                out->matte_written = cm.matte_bits;
            }
        }
        const pattern::mosaic::FilteredLook f = cm.lod->at(t, hit->b1, hit->b2);
        for (int k = 0; k < 3; ++k) out->albedo[k] = f.v[k];
        out->eumelanin = f.v[3];
        out->pheomelanin = f.v[4];
    }
}

void shade(const void *self, const PelageHit *render_hit, PelageShade *out) {
    const ClonalMosaic &cm = *static_cast<const ClonalMosaic *>(self);
    const PelageHit *hit = render_hit;
    PelageHit carried;
    if (cm.transfer) {
        if (render_hit->primitive_id >= cm.transfer->num_render_triangles()) return;
        carried = *render_hit;
        const auto at =
            cm.transfer->map(render_hit->primitive_id, render_hit->b1, render_hit->b2);
        carried.primitive_id = at.tri;
        carried.b1 = at.b1;
        carried.b2 = at.b2;
        carried.footprint *= cm.transfer->scale();
        hit = &carried;
    }
    if (cm.cover && cm.cover->carries(hit->primitive_id)) {
        if (hit != &carried) carried = *render_hit;
        const auto at = cm.cover->map(hit->primitive_id, hit->b1, hit->b2);
        carried.primitive_id = at.tri;
        carried.b1 = at.b1;
        carried.b2 = at.b2;
        hit = &carried;
    }
    // Camera hits with a footprint that sees the exact pattern (most calls): when the
    // previous hit's cells provably answer this one too (coherent_lookup.h), blend them
    // here — what shade_any() would do, the same bits, with less code on the way.
    const uint32_t t = hit->primitive_id;
    if (hit->depth == 0 && hit->footprint <= cm.camera_reuse_up_to &&
        t < cm.num_triangles) {
        const float w = std::max(cm.edge_width, hit->footprint);
        if (w > 0) {
            pattern::mosaic::CoherentLookup &coherent =
                coherent_lookup;  // one TLS look-up
            pattern::mosaic::CoherentLookup::Result n;
            if (coherent.reuse(cm.serial, t, hit->b1, hit->b2, 2 * w, n)) {
                shade_blend(cm, n, w, out);
                return;
            }
            shade_any(cm, hit, out, &coherent);
            return;
        }
    }
    shade_any(cm, hit, out, nullptr);
}

int matte_name(const void *self, uint32_t layer, uint32_t id, char *buf, uint32_t size) {
    const ClonalMosaic &cm = *static_cast<const ClonalMosaic *>(self);
    std::string name;
    if (layer == matte_type && id < cm.types.size())
        name = cm.pattern->types()[id].name;
    else if (layer == matte_cell)
        name = cm.object_name + "/cell " + std::to_string(id);
    else if (layer == matte_lineage)
        name = cm.object_name + "/clone " + std::to_string(id);
    else
        return 0;
    if (size == 0) return 0;
    const size_t n = std::min<size_t>(name.size(), size - 1);
    std::memcpy(buf, name.data(), n);
    buf[n] = 0;
    return 1;
}

const PelageShaderPlugin plugin = {
    PELAGE_SHADER_ABI,
    "clonal_mosaic",
    "Clonal Mosaic cells from a .cells file, closest cell by reverse neighbour mapping "
    "(Teo 2006 ch. 6)",
    params,
    aov_names,
    shader::sdk::guarded_create<make>,
    shade,
    shader::sdk::destroy_instance<ClonalMosaic>,
    matte_names,
    matte_name,
};

}  // namespace

extern "C" PELAGE_EXPORT const PelageShaderPlugin *pelage_shader_plugin(void) {
    return &plugin;
}
