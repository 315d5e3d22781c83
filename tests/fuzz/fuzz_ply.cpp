// libFuzzer target: the PLY reader and the clean-up every subcommand applies after it
// (sim/mesh/mesh_io_ply.cpp, sim/mesh/mesh_clean.cpp). Bad input must end in
// pelage::InputError; any other exception, crash, leak or sanitizer report is a bug.
#include <cstddef>
#include <cstdint>

#include "sim/core/input_error.h"
#include "sim/mesh/mesh_load.h"
#include "tests/fuzz/fuzz_input_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    const std::string &path = pelage::fuzz::write_input_file(data, size, ".ply");
    try {
        const pelage::sim::TriangleMesh mesh = pelage::sim::load_mesh(path);
        // A mesh that loads is usable: every index names a vertex.
        for (const auto &t : mesh.triangles)
            for (auto v : t)
                if (v >= mesh.num_vertices()) __builtin_trap();
    } catch (const pelage::InputError &) {
    }
    return 0;
}
