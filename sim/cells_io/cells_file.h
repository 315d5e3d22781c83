// The .cells file: what `pelage sim` writes (sim/run/cells_data.h packs a run's cells)
// and the shader, the fur, `pelage stats` and `pelage preview` read. Self-contained: it
// carries the CRPS frames and neighbour maps, so tools need no mesh, and the mesh
// identity, so a renderer refuses cells made for another mesh. A leaf library: core and
// the CRPS only, so a reader links none of the simulation.
//
// Layout, version 2, all little-endian, no padding:
//   fixed header (80 bytes)
//     char[8] magic "PELCELLS"   u32 version (1)        u32 num_types (1..8)
//     u64 mesh_hash              u64 num_triangles      u64 num_cells
//     u64 num_maps               u64 seed               u64 params_bytes
//     u64 payload_bytes          u64 reserved (0)
//   payload (payload_bytes)
//     params: params_bytes of UTF-8 JSON (the preset and run options; the preset's
//         anisotropy field as "anisotropy_field", null when it has none, for the fur)
//     type table, per type: u32 name_bytes, name, f32 colour[3] (linear RGB),
//         f32 eumelanin, f32 pheomelanin, f64 division_time (inf = never),
//         f64 initial_probability
//     frames, per triangle 22 × f64: rotation (3×3 row-major), normal (3), y_offset,
//         centre (2), reference vertices v0 v1 v2 (6), area
//     neighbour CSR: u32 nbr_row[num_triangles + 1], u32 nbr[num_maps],
//         maps F[j→i] as 4 × f64 (cos, sin, ax, ay) [num_maps]  (sim/crps/crps.h)
//     cells sorted by (triangle, id): u32 cell_row[num_triangles + 1],
//         f64 x[num_cells], f64 z[num_cells] (2D CRPS, the triangle's local frame),
//         u8 type[num_cells], u32 id[num_cells] (stable id = creation order),
//         u32 founder[num_cells] (the id of the initial cell whose clone it is)
// Version 1 files, identical but without `founder`, are still read (no lineage).
//   u64 checksum: FNV-1a 64 of the header and payload bytes
// Readers check the counts against the file size before allocating, then the checksum,
// then the structure (monotone rows, indices in range); any failure is an InputError.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "sim/crps/crps.h"

namespace pelage::sim {

inline constexpr uint32_t cells_file_version = 2;
inline constexpr uint32_t cells_file_max_types = 8;

// A row of the type table: what the file stores of a cell type (the simulation's
// sim::CellType, sim/mosaic/cell_types.h, is converted by sim/run/cells_data.h).
struct CellsFileType {
    std::string name;
    std::array<float, 3> colour{0.5f, 0.5f, 0.5f};  // linear RGB
    float eumelanin = 0, pheomelanin = 0;           // for the fur shader
    // The mean time between divisions; inf = never.
    double division_time = std::numeric_limits<double>::infinity();
    double initial_probability = 0;
};

struct CellsData {
    uint64_t mesh_hash = 0;
    uint64_t seed = 0;
    std::string params_json;
    std::vector<CellsFileType> types;
    std::vector<CrpsFrame> frames;
    std::vector<uint32_t> nbr_row;
    std::vector<TriId> nbr;
    std::vector<RigidMap2> to_master;  // F[nbr → i], parallel to nbr
    std::vector<uint32_t> cell_row;
    std::vector<double> x, z;
    std::vector<uint8_t> type;
    std::vector<uint32_t> id;
    std::vector<uint32_t> founder;  // parallel to id; empty when read from version 1

    size_t num_triangles() const { return frames.size(); }
    size_t num_cells() const { return x.size(); }
    double area() const;
    bool operator==(const CellsData &) const;
};

// Identity of a mesh: FNV-1a 64 over the triangle count, positions and indices.
uint64_t mesh_hash(const TriangleMesh &mesh);

std::vector<uint8_t> serialize_cells(const CellsData &data);
// `name` is used in error messages.
CellsData parse_cells(const std::vector<uint8_t> &bytes, const std::string &name);

void write_cells_file(const std::string &path, const CellsData &data);  // atomic
CellsData read_cells_file(const std::string &path);                     // one bulk read
// The params JSON alone (the preset and run options the cells were grown with), read
// from the header and the bytes after it: what deciding whether a file is stale, or
// recovering the field it was grown with, needs. The checksum is the whole file's, so it
// is checked when the cells are read.
std::string read_cells_params(const std::string &path);
// The surface the cells were grown on, rebuilt from the file's frames (each reference
// triangle carried back to 3D; corners welded as pelage welds a loaded mesh): the same
// triangles in the same order, so the cells' frames are its CRPS frames.
TriangleMesh surface_mesh(const CellsData &data, const std::string &path);

// InputError when the file was made for another mesh.
void check_cells_match_mesh(const CellsData &data, const TriangleMesh &mesh,
                            const std::string &path);

// The index of the type called `name`, else `fallback` when the file has that many types,
// else −1 (the F and B of a pattern: by name, else types 0 and 1).
int find_type(const CellsData &d, const std::string &name, int fallback);

}  // namespace pelage::sim
