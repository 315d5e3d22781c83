// `pelage cells FILE.cells --export cells.txt`: one line per cell, `face b0 b1 b2 type
// id` — the triangle of the mesh as pelage loads it (the file's face order for triangle
// meshes without degenerate faces), barycentric coordinates in that triangle's corner
// order, the type's index and the stable cell id. For scripts and other tools.
#include <fmt/core.h>

#include <cstdio>
#include <sstream>

#include "apps/common/common.h"
#include "sim/cells_io/cells_file.h"
#include "sim/core/atomic_file.h"

namespace pelage::renderer::cli {
namespace {

struct CellsOptions {
    std::string cells, output;
};

int run(const CellsOptions &o) {
    const sim::CellsData data = sim::read_cells_file(o.cells);
    auto write = [&](std::ostream &out) {
        out << "# face b0 b1 b2 type id   (" << data.num_cells() << " cells; types:";
        for (size_t k = 0; k < data.types.size(); ++k)
            out << " " << k << "=" << data.types[k].name;
        out << ")\n";
        char line[160];
        for (sim::TriId t = 0; t < data.num_triangles(); ++t)
            for (uint32_t k = data.cell_row[t]; k < data.cell_row[t + 1]; ++k) {
                const sim::Vec3d b =
                    sim::barycentric_in(data.frames[t], {data.x[k], data.z[k]});
                std::snprintf(line, sizeof(line), "%u %.9g %.9g %.9g %u %u\n", t, b.x,
                              b.y, b.z, unsigned(data.type[k]), data.id[k]);
                out << line;
            }
    };
    if (o.output.empty() || o.output == "-") {
        std::ostringstream ss;
        write(ss);
        std::fputs(ss.str().c_str(), stdout);
    } else {
        write_file_atomically(o.output, write);
    }
    return 0;
}

}  // namespace

Runner add_cells_command(CLI::App &app) {
    auto o = std::make_shared<CellsOptions>();
    CLI::App *sub = app.add_subcommand(
        "cells", "Export the cells of a .cells file as text (face b0 b1 b2 type id)");
    sub->add_option("cells", o->cells, "The .cells file")->required();
    sub->add_option("--export", o->output,
                    "Output text file ('-' or omitted: standard output)");
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
