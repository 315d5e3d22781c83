// `pelage bench fur`: fur at scale. For each strand count, a child `pelage` process
// grows that many strands on a unit sphere (diffuse skin, a cheetah-like coat's shape:
// combed down, gravity, clumping), builds the Embree curves, renders the scene, and
// renders it again without fur; it reports the strand build time, rays per second with
// and without fur, and its own peak resident memory (getrusage ru_maxrss): one process
// per count, so each peak is that configuration's alone. Prints one JSON object:
// {"runs": [{strands, build_seconds, peak_rss_mb, peak_mb_per_million_strands,
// scene_cpu_seconds_per_million_strands, rays_per_second, rays_per_second_no_fur, ...},
// ...]} (an output contract).
#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "apps/bench/bench.h"
#include "renderer/integrator/render.h"
#include "renderer/scene_file/scene_file.h"
#include "sim/core/input_error.h"
#include "sim/mesh/mesh_load.h"

namespace pelage::renderer::cli {
namespace {

using namespace pelage::renderer;

struct BenchFurOptions {
    std::vector<uint64_t> strands{100000, 1000000};
    std::string res = "320x240";
    int spp = 4, segments = 8;
    std::string curve = "round";
    uint64_t child = 0;  // internal: run one configuration in this process
    ThreadOption threads;
    BenchOutput out;  // the parent's; a child prints its one line regardless
};

constexpr const char *sphere_mesh = "procedural:sphere:20x20";

std::string scene_text(const BenchFurOptions &o, double density, bool with_fur) {
    std::ostringstream s;
    s << R"({"camera": {"position": [0, 0.6, 3.6], "look_at": [0, 0, 0], "fov": 38},
  "lights": [{"type": "environment", "colour": [0.55, 0.68, 0.9], "intensity": 0.8},
             {"type": "distant", "direction": [-0.45, -0.8, -0.4], "angle": 0.53,
              "colour": [1.0, 0.93, 0.82], "intensity": 4.0}],
  "objects": [{"mesh": ")"
      << sphere_mesh << R"(", "normals": "smooth",
               "material": {"shader": "diffuse", "params": {"albedo": [0.6, 0.4, 0.2]}})";
    if (with_fur)
        s << R"(, "fur": {"density": )" << density << R"(, "length": 0.08, "segments": )"
          << o.segments << R"(, "curve": ")" << o.curve
          << R"(", "root_radius": 0.002, "tip_radius": 0.0005, "comb": [0, -1, 0],
               "comb_angle": 25, "gravity": 0.3, "clump": 0.3, "clump_radius": 0.03,
               "max_strands": 50000000})";
    s << R"(},
              {"mesh": "procedural:plane:1x1", "transform": {"scale": 40, "translate": [0, -1, 0]},
               "material": {"shader": "diffuse", "params": {"albedo": 0.35}}}],
  "integrator": {"max_depth": 6, "rr_depth": 3}})";
    return s.str();
}

// One configuration, in this process: prints one JSON line.
int run_child(const BenchFurOptions &o) {
    int width, height;
    parse_resolution(o.res, 16384, &width, &height);
    const auto tbb_threads = o.threads.apply();
    // Density from the sphere's exact (polygonal) area, so the count is as asked.
    const sim::TriangleMesh mesh = sim::load_mesh(sphere_mesh);
    double area = 0;
    for (size_t t = 0; t < mesh.num_triangles(); ++t)
        area += 0.5 * sim::length(mesh.face_normal_unnormalized(sim::TriId(t)));
    const double density = double(o.child) / area;
    const PluginRegistry plugins;
    auto timed_render = [&](const Scene &scene) {
        RenderOptions ro;
        ro.seed = 1;
        const RenderResult r = render(scene, ro);
        return std::pair{r.stats.rays() / std::max(r.seconds, 1e-9), r.seconds};
    };
    auto desc_for = [&](bool fur) {
        SceneDesc d = parse_scene(scene_text(o, density, fur), "bench-fur.json");
        d.film.width = width;
        d.film.height = height;
        d.film.spp = o.spp;
        return d;
    };
    // --- Without fur first, so the peak below is the furry scene's ---
    double rps_bare, sec_bare;
    {
        const Scene bare(desc_for(false), plugins);
        std::tie(rps_bare, sec_bare) = timed_render(bare);
    }
    const Timer t_build;
    const double cpu0 = process_cpu_seconds();
    const Scene furry(desc_for(true), plugins);
    const double scene_seconds = t_build.seconds();
    const double scene_cpu_seconds = process_cpu_seconds() - cpu0;
    const FurGeometry &fur = *furry.fur();
    const auto [rps_fur, sec_fur] = timed_render(furry);
    const size_t n = fur.num_strands();
    const double build = fur.grow_seconds() + fur.embree_seconds();
    // Per million strands: what a groom of a given size costs (the process's base
    // memory and the skin's set-up included, which dominate small counts).
    const double millions = std::max(double(n), 1.0) * 1e-6;
    const double peak = peak_rss_mb();
    const nlohmann::json j = {
        {"strands", n},
        {"peak_mb_per_million_strands", peak / millions},
        {"scene_cpu_seconds_per_million_strands", scene_cpu_seconds / millions},
        {"segments", o.segments},
        {"curve", o.curve},
        {"build_seconds", build},
        {"grow_seconds", fur.grow_seconds()},
        {"embree_seconds", fur.embree_seconds()},
        {"scene_seconds", scene_seconds},
        {"scene_cpu_seconds", scene_cpu_seconds},
        {"strands_per_second", double(n) / std::max(build, 1e-9)},
        {"peak_rss_mb", peak},
        {"rays_per_second", rps_fur},
        {"rays_per_second_no_fur", rps_bare},
        {"render_seconds", sec_fur},
        {"render_seconds_no_fur", sec_bare},
        {"ratio", rps_fur / std::max(rps_bare, 1e-9)},
        {"width", width},
        {"height", height},
        {"spp", o.spp}};
    std::cout << j.dump() << std::endl;
    return 0;
}

int run(const BenchFurOptions &o) {
    if (o.child) return run_child(o);
    if (o.curve != "round" && o.curve != "flat")
        throw InputError("", 0, "--curve",
                         "expected round or flat, got \"" + o.curve + "\"");
    int width, height;
    parse_resolution(o.res, 16384, &width, &height);  // fail here, not in a child
    char self[4096];
    const ssize_t len = readlink("/proc/self/exe", self, sizeof(self) - 1);
    if (len <= 0) {
        std::cerr << "pelage bench fur: cannot find this executable (/proc/self/exe)\n";
        return 1;
    }
    self[len] = 0;
    nlohmann::json runs = nlohmann::json::array();
    for (uint64_t n : o.strands) {
        std::ostringstream cmd;
        cmd << "'" << self << "' bench fur --child " << n << " --res " << o.res
            << " --spp " << o.spp << " --segments " << o.segments << " --curve "
            << o.curve << " --threads " << o.threads.threads;
        FILE *p = popen(cmd.str().c_str(), "r");
        if (!p) {
            std::cerr << "pelage bench fur: cannot start " << cmd.str() << "\n";
            return 1;
        }
        std::string out;
        char buf[4096];
        while (size_t k = fread(buf, 1, sizeof(buf), p)) out.append(buf, k);
        const int status = pclose(p);
        if (status != 0) {
            std::cerr << "pelage bench fur: the run with " << n << " strands failed\n";
            return 1;
        }
        runs.push_back(nlohmann::json::parse(out));
    }
    o.out.emit({{"runs", runs}});
    return 0;
}

}  // namespace

Runner add_bench_fur(CLI::App &bench) {
    auto o = std::make_shared<BenchFurOptions>();
    CLI::App *cmd = bench.add_subcommand(
        "fur", "Fur: strand build time, peak memory, rays/s with and without fur (JSON)");
    cmd->add_option("--strands", o->strands, "Strand counts, one child process each")
        ->check(CLI::Range(uint64_t(1), uint64_t(50'000'000)))
        ->capture_default_str();
    cmd->add_option("--res", o->res, "Render resolution WxH")->capture_default_str();
    cmd->add_option("--spp", o->spp, "Samples per pixel")
        ->check(CLI::Range(1, 4096))
        ->capture_default_str();
    cmd->add_option("--segments", o->segments, "Segments per strand")
        ->check(CLI::Range(2, 64))
        ->capture_default_str();
    cmd->add_option("--curve", o->curve, "round (B-spline tubes) or flat (ribbons)")
        ->capture_default_str();
    cmd->add_option("--child", o->child, "Internal: run one strand count in this process")
        ->group("");
    o->threads.add_to(*cmd);
    o->out.add_to(*cmd);
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
