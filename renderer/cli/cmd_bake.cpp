// `pelage bake FILE.cells --mesh M --res 4096 -o pattern.exr --obj out.obj`: the mosaic
// as an ordinary texture on an undistorted CRPS atlas, and the mesh with those UVs.
#include <fmt/core.h>

#include "renderer/cli/common.h"
#include "renderer/image/image_output.h"
#include "shader/clonal_mosaic/bake.h"
#include "sim/core/input_error.h"
#include "sim/mesh/mesh_write_obj.h"

namespace pelage::renderer::cli {
namespace {

struct BakeOptions {
    std::string cells, mesh, output, obj;
    int res = 4096, gutter = 2;
    ThreadOption threads;
};

int run(const BakeOptions &o) {
    const auto control = o.threads.apply();
    if (o.output.size() < 4 || o.output.substr(o.output.size() - 4) != ".exr")
        throw InputError("", 0, "-o",
                         "\"" + o.output + "\": the atlas is written as OpenEXR (.exr)");
    const Timer timer;
    const shader::clonal_mosaic::MosaicPattern pattern(o.cells, o.mesh);
    if (pattern.transfer())
        throw InputError(o.mesh, 0, "--mesh",
                         "bake lays out the triangles the cells were grown on: give that "
                         "mesh (this one is another mesh of the same shape)");
    shader::clonal_mosaic::BakedPattern baked;
    try {
        baked = shader::clonal_mosaic::bake_pattern(pattern, o.res, o.gutter);
    } catch (const std::invalid_argument &e) {
        throw InputError("", 0, "--res", e.what());
    }
    renderer::ImageMetadata meta;
    meta.software = "pelage " PELAGE_VERSION " bake";
    meta.scene = o.cells;
    renderer::write_exr(o.output, o.res, o.res, baked.pixels,
                        {"R", "G", "B", "A", "shader.cell_type", "shader.cell_id"}, false,
                        meta);
    if (!o.obj.empty()) {
        std::vector<sim::Vec2d> uvs;
        for (sim::TriId t = 0; t < pattern.num_triangles(); ++t)
            for (int c = 0; c < 3; ++c) uvs.push_back(baked.atlas.uv(t, c));
        sim::write_obj(o.obj, pattern.surface().mesh, uvs,
                       "pelage bake: CRPS atlas UVs for " + o.output);
    }
    const double used = double(baked.texels_inside) / (double(o.res) * o.res);
    fmt::print(
        "pelage bake: {} ({}x{}): {:.1f} % of texels inside triangles, {:.1f} texels per "
        "unit, {:.2f} s\n",
        o.output, o.res, o.res, 100 * used, baked.atlas.texels_per_unit, timer.seconds());
    return 0;
}

}  // namespace

Runner add_bake_command(CLI::App &app) {
    auto o = std::make_shared<BakeOptions>();
    CLI::App *sub = app.add_subcommand(
        "bake",
        "Bake a mosaic into a texture atlas (EXR) and write the mesh with its UVs");
    sub->add_option("cells", o->cells, "The .cells file")->required();
    sub->add_option("--mesh", o->mesh, "The mesh the cells were grown on")->required();
    sub->add_option("--res", o->res, "Atlas resolution (square)")
        ->check(CLI::Range(16, 32768));
    sub->add_option("--gutter", o->gutter, "Texels of padding around each triangle")
        ->check(CLI::Range(0, 64));
    sub->add_option("-o,--output", o->output, "Atlas image (.exr)")->required();
    sub->add_option("--obj", o->obj, "Also write the mesh as OBJ with the atlas UVs");
    o->threads.add_to(*sub);
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
