// `pelage bake FILE.cells (--mesh M | --uv-from M) --res 4096 -o pattern.<UDIM>.exr
// --obj out.obj --glb out.glb`: the mosaic as an ordinary texture, on the mesh's own UVs
// (UDIM tiles) or on an undistorted CRPS atlas, and the mesh with those UVs and its
// normals, as OBJ or as one binary glTF with the texture inside (renderer/export).
#include <fmt/core.h>

#include <cstdio>
#include <filesystem>
#include <optional>

#include "apps/common/common.h"
#include "pattern/bake/bake.h"
#include "renderer/export/glb_writer.h"
#include "renderer/export/texture_png.h"
#include "renderer/image/image_output.h"
#include "sim/core/input_error.h"
#include "sim/crps/surface.h"
#include "sim/mesh/mesh_load.h"
#include "sim/mesh/mesh_write_obj.h"

namespace pelage::renderer::cli {
namespace {

namespace cm = pattern::bake;

struct BakeOptions {
    std::string cells, mesh, uv_from, output, obj, glb, res = "4096";
    int gutter = 4;
    ThreadOption threads;
    QuietOption quiet;
    StatsJsonOption stats_json;
};

constexpr const char *udim_token = "<UDIM>";

// The output's name for one tile: <UDIM> replaced by its number.
std::string tile_path(const std::string &pattern, int udim) {
    std::string s = pattern;
    const size_t at = s.find(udim_token);
    if (at != std::string::npos)
        s.replace(at, std::string(udim_token).size(), std::to_string(udim));
    return s;
}

int run(const BakeOptions &o) {
    const auto control = o.threads.apply();
    if (o.mesh.empty() == o.uv_from.empty())
        throw InputError("", 0, "--mesh",
                         "give --mesh (bake into an atlas) or --uv-from (bake into that "
                         "mesh's UVs), one of them");
    if (o.output.size() < 4 || o.output.substr(o.output.size() - 4) != ".exr")
        throw InputError(
            "", 0, "-o",
            "\"" + o.output + "\": the texture is written as OpenEXR (.exr)");
    if (!o.glb.empty() && (o.glb.size() < 4 || o.glb.substr(o.glb.size() - 4) != ".glb"))
        throw InputError("", 0, "--glb",
                         "\"" + o.glb + "\": the mesh is written as binary glTF (.glb)");
    // N is a square (the atlas's shape, and the usual UDIM tile); WxH otherwise.
    const Resolution res =
        parse_resolution(o.res, 32768, ResolutionForm::or_longer_side, "--res", 16);
    const int width = res.width, height = res.height;

    const Timer timer;
    const std::string &mesh_path = o.uv_from.empty() ? o.mesh : o.uv_from;
    renderer::ImageMetadata meta;
    meta.software = "pelage " PELAGE_VERSION " bake";
    meta.scene = o.cells;
    std::vector<std::string> written;
    std::vector<float> glb_pixels;
    nlohmann::json tiles = nlohmann::json::array();
    auto write_tile = [&](const cm::BakedTile &tile) {
        const std::string path = tile_path(o.output, tile.udim);
        renderer::write_exr(path, width, height, tile.pixels,
                            cm::BakeResult::channel_names(), false, meta);
        written.push_back(path);
        tiles.push_back({{"udim", tile.udim}, {"file", path}});
        if (!o.glb.empty()) glb_pixels = tile.pixels;  // the one tile (checked below)
    };
    const pattern::mosaic::MosaicPattern pattern(o.cells, mesh_path);
    cm::BakeResult baked;
    std::optional<cm::Atlas> atlas;
    sim::TriangleMesh uv_mesh;
    if (o.uv_from.empty()) {
        // Cells grown on a simplified copy (pelage sim --surface auto) or another mesh of
        // the shape: the atlas lays out the mesh given, carried onto theirs.
        std::optional<sim::Surface> render;
        if (pattern.transfer()) render = sim::build_surface(o.mesh);
        try {
            cm::BakedAtlas a = cm::bake_atlas(pattern, width, height, o.gutter,
                                              render ? &*render : nullptr);
            baked = std::move(a.image);
            atlas = std::move(a.atlas);
        } catch (const std::invalid_argument &e) {
            throw InputError("", 0, "--res", e.what());
        }
        if (render) uv_mesh = std::move(render->mesh);
    } else {
        // The same loader as the pattern's: the same triangles in the same order.
        uv_mesh = sim::load_mesh(o.uv_from);
        if (uv_mesh.corner_uvs.size() != 3 * uv_mesh.num_triangles() ||
            uv_mesh.num_triangles() == 0)
            throw InputError(o.uv_from, 0, "vt",
                             "the mesh has no UVs (an OBJ with vt lines and faces "
                             "v/vt is needed)");
        cm::BakeLayout layout;
        layout.mesh = &uv_mesh;
        layout.corner_uvs = uv_mesh.corner_uvs;
        layout.transfer = pattern.transfer();
        layout.width = width;
        layout.height = height;
        layout.gutter = o.gutter;
        std::vector<int> udims;
        try {
            udims = cm::udim_tiles(uv_mesh, uv_mesh.corner_uvs);
        } catch (const std::invalid_argument &e) {
            throw InputError(o.uv_from, 0, "vt", e.what());
        }
        if (udims.size() > 1 && o.output.find(udim_token) == std::string::npos)
            throw InputError("", 0, "-o",
                             "\"" + o.output + "\": the UVs span " +
                                 std::to_string(udims.size()) +
                                 " UDIM tiles; name the output with <UDIM>, e.g. "
                                 "pattern.<UDIM>.exr");
        if (udims.size() > 1 && !o.glb.empty())
            throw InputError(
                o.uv_from, 0, "--glb",
                "the UVs span " + std::to_string(udims.size()) +
                    " UDIM tiles; a glTF material takes one texture (lay "
                    "the UVs out in 0-1, or bake into an atlas with --mesh)");
        // Each tile is written as soon as it is baked: one tile in memory at a time.
        baked = cm::bake_layout(pattern, layout,
                                [&](cm::BakedTile &&tile) { write_tile(tile); });
        if (baked.texels_overlapped > 0)
            fmt::print(stderr,
                       "pelage bake: warning: {}: {:.2f} % of the covered texels lie "
                       "under two or more UV triangles (overlapping UVs); they show the "
                       "first triangle's pattern\n",
                       o.uv_from, 100 * baked.overlap_share());
        if (baked.degenerate_triangles > 0)
            fmt::print(stderr,
                       "pelage bake: warning: {}: {} triangles have no UV area and are "
                       "not baked\n",
                       o.uv_from, baked.degenerate_triangles);
    }

    for (const cm::BakedTile &tile : baked.tiles) write_tile(tile);
    if (!o.obj.empty()) {
        if (atlas) {
            const sim::TriangleMesh &mesh =
                pattern.transfer() ? uv_mesh : pattern.surface().mesh;
            std::vector<sim::Vec2d> uvs;
            for (sim::TriId t = 0; t < mesh.num_triangles(); ++t)
                for (int c = 0; c < 3; ++c) uvs.push_back(atlas->uv(t, c));
            sim::write_obj(o.obj, mesh, uvs,
                           "pelage bake: CRPS atlas UVs for " + o.output);
        } else {
            sim::write_obj(o.obj, uv_mesh, uv_mesh.corner_uvs,
                           "pelage bake: the UVs of " + o.uv_from + " for " + o.output);
        }
    }
    if (!o.glb.empty()) {
        const sim::TriangleMesh &mesh =
            atlas && !pattern.transfer() ? pattern.surface().mesh : uv_mesh;
        std::vector<double> positions;
        for (const sim::Vec3d &p : mesh.positions)
            positions.insert(positions.end(), {p.x, p.y, p.z});
        std::vector<uint32_t> triangles;
        std::vector<float> normals, uvs;
        for (sim::TriId t = 0; t < mesh.num_triangles(); ++t)
            for (int c = 0; c < 3; ++c) {
                triangles.push_back(mesh.triangles[t][c]);
                const sim::Vec2d uv =
                    atlas ? atlas->uv(t, c) : mesh.corner_uvs[3 * t + c];
                uvs.insert(uvs.end(), {float(uv.x), float(uv.y)});
                if (!mesh.corner_normals.empty()) {
                    const sim::Vec3d n = mesh.corner_normals[3 * t + c];
                    normals.insert(normals.end(), {float(n.x), float(n.y), float(n.z)});
                }
            }
        const std::string png =
            renderer::png_bytes(width, height,
                                renderer::srgb_rgb8(glb_pixels, cm::BakeResult::channels,
                                                    size_t(width) * size_t(height)),
                                o.glb + ".texture.png");
        renderer::write_glb(
            o.glb,
            renderer::glb_mesh(std::filesystem::path(mesh_path).stem().string(),
                               positions, triangles, normals, uvs),
            png, "pelage " PELAGE_VERSION " bake");
    }
    const double seconds = timer.seconds();
    if (o.stats_json.wanted()) {
        nlohmann::json j = {
            {"cells", o.cells},
            {"mesh", mesh_path},
            {"layout", atlas ? "atlas" : "uv"},
            {"width", width},
            {"height", height},
            {"tiles", tiles},
            {"coverage", baked.coverage()},
            {"texels_inside", baked.texels_inside},
            {"texels_gutter", baked.texels_gutter},
            {"overlap_share", baked.overlap_share()},
            {"degenerate_triangles", baked.degenerate_triangles},
            {"seconds", seconds},
        };
        if (!o.glb.empty()) j["glb"] = o.glb;
        if (atlas) {
            j["charts"] = atlas->num_charts;
            j["texels_per_unit"] = atlas->texels_per_unit;
        }
        o.stats_json.write(j);
    }
    if (!o.quiet) {
        fmt::print(
            "pelage bake: {} ({}x{}, {} tile{}): {:.1f} % of texels inside "
            "triangles",
            written.size() == 1 ? written[0] : o.output, width, height, written.size(),
            written.size() == 1 ? "" : "s", 100 * baked.coverage());
        if (atlas)
            fmt::print(", {} charts, {:.1f} texels per unit", atlas->num_charts,
                       atlas->texels_per_unit);
        if (!o.glb.empty()) fmt::print("; the textured mesh in {}", o.glb);
        fmt::print(", {:.2f} s\n", seconds);
    }
    return 0;
}

}  // namespace

Runner add_bake_command(CLI::App &app) {
    auto o = std::make_shared<BakeOptions>();
    CLI::App *sub = app.add_subcommand(
        "bake",
        "Bake a mosaic into a texture (EXR) on the mesh's UVs or an undistorted atlas");
    sub->add_option("cells", o->cells, "The .cells file")->required();
    sub->add_option("--mesh", o->mesh,
                    "Bake into an atlas of this mesh (the one the cells were grown on)");
    sub->add_option("--uv-from", o->uv_from,
                    "Bake into this mesh's own UVs (an OBJ with vt; the cells' mesh or "
                    "another mesh of its shape); UDIM tiles when they span several");
    sub->add_option("--res", o->res,
                    "Texels of the atlas or of each UDIM tile: WxH, or N "
                    "for NxN (default 4096)");
    sub->add_option("--gutter", o->gutter,
                    "Texels beyond each chart's border filled from the surface")
        ->check(CLI::Range(0, 64));
    sub->add_option("-o,--output", o->output,
                    "Texture (.exr); <UDIM> in the name stands for the tile number")
        ->required();
    sub->add_option("--obj", o->obj,
                    "Also write the mesh as OBJ with its UVs and normals");
    sub->add_option("--glb", o->glb,
                    "Also write the mesh, its UVs and the texture (sRGB PNG inside) as "
                    "one binary glTF (.glb), for web viewers and DCCs");
    o->stats_json.add_to(*sub, "coverage, tiles and time");
    o->quiet.add_to(*sub);
    o->threads.add_to(*sub);
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
