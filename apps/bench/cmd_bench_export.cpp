// `pelage bench export SCENE`: what `pelage export` costs per million strands. The
// scene's fur densities are scaled (--density-scale) to the size measured, the scene is
// set up once per repeat (patterns, strands) and its coat exported to a scratch folder;
// the median of the repeats' export times (gathering the coat and writing the stage),
// the stage's size, and both per million strands.
#include <fmt/core.h>

#include <algorithm>
#include <filesystem>

#include "apps/bench/bench.h"
#include "renderer/export/export_job.h"
#include "renderer/job/render_job.h"

namespace pelage::renderer::cli {
namespace {

namespace fs = std::filesystem;

struct BenchExportOptions {
    std::string scene = "scenes/fur_cow_giraffe.json";
    double density_scale = 3;
    int repeats = 3;
    ThreadOption threads;
    BenchOutput out;
};

int run(const BenchExportOptions &o) {
    const auto control = o.threads.apply();
    ExportJob job;
    job.scene = render_job_from_file(o.scene).scene;
    for (ObjectDesc &ob : job.scene.objects)
        if (ob.fur) ob.fur->density *= o.density_scale;
    const fs::path scratch =
        fs::temp_directory_path() / fmt::format("pelage-bench-export-{}", ::getpid());
    fs::create_directories(scratch);
    job.output = (scratch / "coat.usda").string();
    std::vector<double> seconds, setup;
    ExportReport report;
    try {
        for (int r = 0; r < o.repeats; ++r) {
            report = run_export(job);
            seconds.push_back(report.write_seconds);
            setup.push_back(report.setup_seconds);
        }
    } catch (...) {
        fs::remove_all(scratch);
        throw;
    }
    fs::remove_all(scratch);
    std::sort(seconds.begin(), seconds.end());
    std::sort(setup.begin(), setup.end());
    const double median = seconds[seconds.size() / 2];
    const double millions = double(report.strands) / 1e6;
    o.out.emit({{"scene", o.scene},
                {"density_scale", o.density_scale},
                {"threads", o.threads.threads},
                {"strands", report.strands},
                {"points", report.points},
                {"triangles", report.triangles},
                {"bytes", report.bytes},
                {"repeats", o.repeats},
                {"setup_seconds", setup[setup.size() / 2]},
                {"export_seconds", median},
                {"export_seconds_all", seconds},
                {"seconds_per_million_strands", millions > 0 ? median / millions : 0.0},
                {"mb_per_million_strands",
                 millions > 0 ? double(report.bytes) / 1e6 / millions : 0.0}});
    return 0;
}

}  // namespace

Runner add_bench_export(CLI::App &bench) {
    auto o = std::make_shared<BenchExportOptions>();
    CLI::App *cmd = bench.add_subcommand(
        "export", "pelage export's time and stage size per million strands");
    cmd->add_option("scene", o->scene, "A scene with fur")->capture_default_str();
    cmd->add_option("--density-scale", o->density_scale,
                    "Multiply every fur density by this (3: about a million strands on "
                    "the default scene)")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    cmd->add_option("--repeats", o->repeats, "Exports measured (the median is reported)")
        ->check(CLI::Range(1, 100))
        ->capture_default_str();
    o->threads.add_to(*cmd);
    o->out.add_to(*cmd);
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
