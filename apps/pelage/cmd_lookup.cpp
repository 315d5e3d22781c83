// `pelage lookup FILE.cells --mesh M --points PTS.txt`: for each `face b0 b1 b2` line,
// the nearest cell's `id type distance` as the clonal_mosaic material finds it (the same
// MosaicPattern and search). Faces are triangles of the mesh as pelage loads it: the one
// the cells were grown on, or another of its shape (shader/clonal_mosaic/
// surface_transfer.h). --stats-json keys: cells, mesh, points, queries, found,
// mean_distance, max_distance, seconds_load, seconds_lookup, and the closest-cell index's
// build: index.{seconds, bytes, rounds, radius_in_spacings, windows, windows_settled,
// window_bytes}.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "apps/common/common.h"
#include "pattern/mosaic/pattern.h"
#include "sim/core/input_error.h"
#include "sim/core/text_lines.h"

namespace pelage::renderer::cli {
namespace {

struct LookupOptions {
    std::string cells, mesh, points;
    StatsJsonOption stats_json;
};

int run(const LookupOptions &o) {
    const Timer load;
    const pattern::mosaic::MosaicPattern pattern(o.cells, o.mesh);
    const double seconds_load = load.seconds();
    std::ifstream in(o.points, std::ios::binary);
    if (!in) throw InputError(o.points, 0, "", "cannot open file");
    // Parse everything first: a bad line fails the run before anything is printed.
    struct Query {
        sim::TriId face;
        float b1, b2;
    };
    std::vector<Query> queries;
    std::string line;
    for (size_t line_no = 1;; ++line_no) {
        const sim::LineRead r = sim::read_line(in, line);
        if (r == sim::LineRead::end_of_file) break;
        if (r == sim::LineRead::too_long)
            throw InputError(o.points, line_no, "", "line too long");
        if (const auto hash = line.find('#'); hash != std::string::npos)
            line.resize(hash);
        std::istringstream ss(line);
        long long face;
        double b0, b1, b2;
        std::string extra;
        if (!(ss >> face)) {
            if (line.find_first_not_of(" \t\r") == std::string::npos) continue;  // blank
            throw InputError(o.points, line_no, "", "expected `face b0 b1 b2`");
        }
        if (!(ss >> b0 >> b1 >> b2) || (ss >> extra))
            throw InputError(o.points, line_no, "", "expected `face b0 b1 b2`");
        const size_t faces = pattern.transfer()
                                 ? pattern.transfer()->num_render_triangles()
                                 : pattern.num_triangles();
        if (face < 0 || size_t(face) >= faces)
            throw InputError(o.points, line_no, "",
                             "face " + std::to_string(face) + " out of range [0, " +
                                 std::to_string(faces) + ")");
        if (!std::isfinite(b0) || !std::isfinite(b1) || !std::isfinite(b2) ||
            std::abs(b0 + b1 + b2 - 1) > 1e-4 || b0 < -1e-4 || b1 < -1e-4 || b2 < -1e-4)
            throw InputError(o.points, line_no, "",
                             "barycentric coordinates must be >= 0 and sum to 1");
        queries.push_back({sim::TriId(face), float(b1), float(b2)});
    }
    const Timer lookup;
    size_t found = 0;
    double sum = 0, max = 0;
    for (const Query &q : queries) {
        // As the renderer: carried onto the simulation surface when the mesh is another,
        // and onto its cell-bearing part from a piece without cells.
        const pattern::transfer::SurfaceTransfer::Target at =
            pattern.locate(q.face, q.b1, q.b2);
        const pattern::mosaic::ClosestCell c =
            pattern.index().find_nearest(at.tri, at.b1, at.b2);
        if (c.index == pattern::mosaic::ClosestCell::none) {
            std::printf("none none inf\n");
            continue;
        }
        std::printf("%u %u %.9g\n", pattern.cells().id[c.index],
                    unsigned(pattern.cells().type[c.index]), c.f1);
        ++found;
        sum += c.f1;
        max = std::max(max, double(c.f1));
    }
    const pattern::mosaic::ClosestCellStats &ix = pattern.index().stats();
    o.stats_json.write(
        {{"cells", o.cells},
         {"mesh", o.mesh},
         {"points", o.points},
         {"queries", queries.size()},
         {"found", found},
         {"mean_distance", found ? sum / double(found) : 0.0},
         {"max_distance", max},
         {"seconds_load", seconds_load},
         {"seconds_lookup", lookup.seconds()},
         {"index",
          {{"seconds", ix.build_seconds},
           {"bytes", ix.bytes},
           {"rounds", ix.geodesic_rounds},
           {"radius_in_spacings",
            ix.geodesic_radius / std::max(pattern.index().spacing(), 1e-300)},
           {"windows", ix.geodesic_windows},
           {"windows_settled", ix.geodesic_work},
           {"window_bytes", ix.geodesic_bytes}}},
         // Pieces of the simulation surface without cells of their own
         // (pattern/transfer/cell_cover.h).
         {"cover",
          {{"carried_triangles", pattern.cover().report().carried_triangles},
           {"carried_pieces", pattern.cover().report().carried_pieces},
           {"pieces", pattern.cover().report().pieces},
           {"carried_area_share", pattern.cover().report().carried_area_share},
           {"without_cell_share", pattern.cover().report().without_cell_share}}}});
    return 0;
}

}  // namespace

Runner add_lookup_command(CLI::App &app) {
    auto o = std::make_shared<LookupOptions>();
    CLI::App *sub = app.add_subcommand(
        "lookup",
        "Nearest cell (id type distance) of surface points, as the renderer finds it");
    sub->add_option("cells", o->cells, "The .cells file")->required();
    sub->add_option("--mesh", o->mesh,
                    "The mesh the points lie on: the one the cells were grown on, or "
                    "another of its "
                    "shape (subdivided, remeshed, rescaled)")
        ->required();
    sub->add_option("--points", o->points, "Text file of `face b0 b1 b2` lines")
        ->required();
    o->stats_json.add_to(*sub, "the query count and the distances found");
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
