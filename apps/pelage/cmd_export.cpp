// `pelage export SCENE -o coat.usda`: the coat for other tools (Houdini, Blender, Unity,
// Unreal) as an OpenUSD stage: each patterned skin with its pattern as primvars (and a
// baked texture with --texture), each fur layer as BasisCurves coloured by the cell
// under each root; an animation's frames as time samples (renderer/export).
#include <fmt/core.h>

#include <memory>
#include <string>
#include <vector>

#include "apps/common/common.h"
#include "apps/pelage/export_report.h"
#include "renderer/export/export_job.h"
#include "renderer/job/render_job.h"

namespace pelage::renderer::cli {
namespace {

struct ExportOptions {
    std::string scene, output, frames;
    std::vector<std::string> objects;
    bool no_fur = false;
    int texture = 0;
    double meters_per_unit = 1;
    uint64_t max_points = ExportJob{}.max_points;
    ThreadOption threads;
    QuietOption quiet;
    StatsJsonOption stats_json;
};

int run(const ExportOptions &o) {
    const auto control = o.threads.apply();
    ExportJob job;
    job.scene = render_job_from_file(o.scene).scene;
    job.output = o.output;
    job.objects = o.objects;
    job.fur = !o.no_fur;
    job.frames = o.frames;
    job.texture_size = o.texture;
    job.meters_per_unit = o.meters_per_unit;
    job.max_points = o.max_points;
    job.command = "pelage export " + o.scene;
    const ExportReport report = run_export_reported(job, "pelage export", o.quiet);
    if (o.stats_json.wanted()) o.stats_json.write(export_report_json(report));
    return 0;
}

}  // namespace

Runner add_export_command(CLI::App &app) {
    auto o = std::make_shared<ExportOptions>();
    CLI::App *sub = app.add_subcommand(
        "export",
        "Export the coat as OpenUSD (.usda): patterned skins with their pattern, fur "
        "as curves coloured by the cell under each root");
    sub->add_option("scene", o->scene, "Scene file (.json)")->required();
    sub->add_option("-o,--output", o->output, "The stage (.usda)")->required();
    sub->add_option("--object", o->objects,
                    "Export this object (by name; repeat for more); default: every "
                    "patterned object");
    sub->add_flag("--no-fur", o->no_fur, "Leave the fur out");
    sub->add_option("--frames", o->frames,
                    "Frames of the animation, e.g. 1-48 (default: every frame when an "
                    "object moves, else a still)");
    sub->add_option("--texture", o->texture,
                    "Bake each skin's pattern into an N×N PNG beside the stage (its own "
                    "UVs in 0-1, else an atlas), bound through UsdPreviewSurface")
        ->check(CLI::Range(16, 16384));
    sub->add_option("--meters-per-unit", o->meters_per_unit,
                    "The stage's metersPerUnit: scene units in metres")
        ->check(CLI::PositiveNumber);
    sub->add_option("--max-points", o->max_points,
                    "The most fur control points to hold over all frames (memory)")
        ->check(CLI::PositiveNumber);
    o->stats_json.add_to(*sub, "what was written and the time it took");
    o->quiet.add_to(*sub);
    o->threads.add_to(*sub);
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
