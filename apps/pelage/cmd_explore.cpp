// `pelage explore [MESH]`: a local web page to tweak a preset and watch its pattern form
// on the mesh (apps/explore): the server binds to 127.0.0.1 unless --host says
// otherwise, prints the URL and serves until Ctrl-C. Renders and saved scenes go
// through the same scene as `pelage look` writes (look_scene.h) and `pelage render`.
#include <fmt/core.h>
#include <signal.h>
#include <stdlib.h>

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>

#include "apps/common/common.h"
#include "apps/explore/explore_server.h"
#include "apps/explore/explore_session.h"
#include "renderer/camera/auto_frame.h"
#include "renderer/camera/body_facing.h"
#include "renderer/job/render_job.h"
#include "renderer/look/look_scene.h"
#include "sim/core/atomic_file.h"
#include "sim/core/input_error.h"
#include "sim/mosaic/preset.h"

namespace pelage::renderer::cli {
namespace {

namespace fs = std::filesystem;

struct ExploreCliOptions {
    std::string mesh, preset = "giraffe-reticulata", host = "127.0.0.1", out = ".";
    int port = 8765;
    uint64_t seed = 1;
    ThreadOption threads;
};

// The shipped presets the page offers, in name order: those the parser accepts and
// whose growth, if any, names no mesh file.
std::vector<std::pair<std::string, std::string>> shipped_presets() {
    std::vector<std::pair<std::string, std::string>> out;
    const fs::path dir = data_path("scenes/presets");
    std::error_code ec;
    for (const auto &e : fs::directory_iterator(dir, ec)) {
        if (e.path().extension() != ".json") continue;
        std::ifstream in(e.path(), std::ios::binary);
        std::string text(std::istreambuf_iterator<char>(in), {});
        try {
            const sim::Preset p = sim::parse_preset(text, e.path().string());
            if (p.growth && p.growth->has_mesh_keys()) continue;
            // The page edits and sends back whole presets: one that extends another is
            // sent merged, as the base's document with its own colours.
            if (!p.extends.empty()) text = p.json_text;
        } catch (const InputError &) {
            continue;
        }
        out.emplace_back(e.path().stem().string(), std::move(text));
    }
    std::sort(out.begin(), out.end());
    return out;
}

// The look's scene: the mesh framed as `pelage look` frames it, its pattern the
// explored preset and seed, grown into `cells`.
LookSetup explore_setup(const explore::ExploreSession &session) {
    const sim::TriangleMesh &m = session.input_surface().mesh;
    std::vector<Vec3f> points;
    for (const auto &p : m.positions)
        points.push_back({float(p.x), float(p.y), float(p.z)});
    std::vector<std::array<uint32_t, 3>> triangles;
    for (const auto &t : m.triangles)
        triangles.push_back({uint32_t(t[0]), uint32_t(t[1]), uint32_t(t[2])});
    FramingRequest request;
    request.up = {0, 1, 0};
    request.aspect = 16.0f / 9.0f;
    // Turned to the head, as `pelage look` is (body_facing.h).
    const BodyFacing facing =
        body_facing(points, triangles, request.up, format_front(session.mesh()));
    request.long_axis = facing.long_axis;
    request.side_axis = facing.side_axis;
    LookSetup s;
    s.framing = frame_points(points, request);
    s.object_name = "animal";
    // Denoised, as `pelage look --denoise`: the page's preview and the saved scene alike.
    s.denoise = true;
    return s;
}

// A render for the page says nothing but its warnings.
class Warnings : public RenderObserver {
  public:
    void warning(const std::string &line) override {
        std::fprintf(stderr, "pelage explore: %s\n", line.c_str());
    }
};

int run(const ExploreCliOptions &o) {
    // Ctrl-C and SIGTERM stop the server from a thread of their own (started below); the
    // workers finish and the working folder is removed. Blocked before any thread starts,
    // so that every thread inherits the mask and none dies of them. A shell starts
    // background jobs with SIGINT ignored, and an ignored signal never reaches sigwait:
    // the default is restored.
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    sigset_t stop_signals;
    sigemptyset(&stop_signals);
    sigaddset(&stop_signals, SIGINT);
    sigaddset(&stop_signals, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);
    const auto control = o.threads.apply();
    std::string mesh = o.mesh;
    if (mesh.empty()) {
        mesh = data_path("scenes/meshes/cow.off");
        if (!fs::exists(mesh))
            throw InputError("", 0, "MESH",
                             "no mesh given and the sample cow (" + mesh +
                                 ") is not there: give a mesh, or fetch the samples with "
                                 "scenes/fetch_meshes.sh");
    }
    if (!fs::is_directory(o.out))
        throw InputError("", 0, "--out", "\"" + o.out + "\": no such folder");
    if (o.port < 0 || o.port > 65535)
        throw InputError("", 0, "--port", "expected 0 (any free port) to 65535");
    // The starting preset: checked now, so a bad one fails before the server starts.
    const sim::Preset start = sim::load_preset(o.preset, data_path("scenes/presets"));
    if (o.host != "127.0.0.1" && o.host != "localhost")
        std::fprintf(stderr,
                     "pelage explore: warning: listening on %s: anyone who reaches this "
                     "machine can use the page, save files into %s and run renders\n",
                     o.host.c_str(), fs::absolute(o.out).string().c_str());

    char work_template[] = "/tmp/pelage-explore-XXXXXX";
    if (!mkdtemp(work_template))
        throw std::runtime_error("cannot make a working folder in /tmp");
    const std::string work = work_template;
    struct Cleanup {
        std::string dir;
        ~Cleanup() {
            std::error_code ec;
            fs::remove_all(dir, ec);
        }
    } cleanup{work};

    explore::ExploreOptions eo;
    eo.mesh = mesh;
    eo.preset_dir = data_path("scenes/presets");
    eo.work_dir = work;
    explore::ExploreSession session(eo);
    const LookSetup base = explore_setup(session);
    const fs::path out = fs::absolute(o.out).lexically_normal();

    explore::ExploreHooks hooks;
    hooks.render = [&](const explore::ExploreResult &r, int width, int height, int spp,
                       const std::string &png) {
        LookSetup s = base;
        s.mesh = mesh_reference(mesh, work);
        s.cells = r.cells_path;
        s.preset = r.preset_path;
        s.seed = r.seed;
        s.width = width;
        s.height = height;
        s.spp = spp;
        s.denoise = spp >= 2;  // the first pass's one sample has no halves to compare
        s.output = work + "/render.exr";
        s.preview = png;
        // The scene a save writes, rendered from memory (it anchors in the work folder).
        const RenderJob job = render_job_from_text(format_scene_json(look_scene(s)),
                                                   work + "/render_scene.json");
        Warnings warnings;
        run_render_job(job, warnings);
    };
    hooks.save = [&](const explore::ExploreResult &r, const std::string &stem) {
        const std::string preset_file = stem + "_preset.json";
        LookSetup s = base;
        s.mesh = mesh_reference(mesh, out);
        s.cells = stem + ".cells";
        s.preset = preset_file;
        s.seed = r.seed;
        s.output = stem + ".exr";
        s.preview = stem + "_preview.png";
        const std::vector<std::string> files = {(out / preset_file).string(),
                                                (out / s.cells).string(),
                                                (out / (stem + ".json")).string()};
        write_file_atomically(files[0], [&](std::ostream &os) { os << r.preset_text; });
        fs::copy_file(r.cells_path, files[1] + ".tmp",
                      fs::copy_options::overwrite_existing);
        fs::rename(files[1] + ".tmp", files[1]);
        const std::string text = format_scene_json(look_scene(s));
        write_file_atomically(files[2], [&](std::ostream &os) { os << text; });
        return files;
    };

    explore::ExploreServer server(session, data_path("explore"), shipped_presets(),
                                  hooks);
    const int port = server.bind(o.host, o.port);
    std::thread waiter([&] {
        int sig = 0;
        sigwait(&stop_signals, &sig);
        session.shutdown();  // long polls answer now, so the server's threads end
        server.stop();
    });
    session.submit(start.json_text, o.seed);
    fmt::print("pelage explore: {} with {} — open http://{}:{}/ (Ctrl-C stops)\n", mesh,
               start.name, o.host, port);
    std::fflush(stdout);
    server.run();
    // Stopped by a signal: the waiter has returned. Stopped otherwise: wake it.
    pthread_kill(waiter.native_handle(), SIGTERM);
    waiter.join();
    return 0;
}

}  // namespace

Runner add_explore_command(CLI::App &app) {
    auto o = std::make_shared<ExploreCliOptions>();
    CLI::App *sub = app.add_subcommand(
        "explore",
        "Tweak a preset in a web page and watch its pattern form on the mesh, live");
    sub->add_option("mesh", o->mesh,
                    "Mesh file (or FILE#NAME, procedural:...; default: the sample cow)");
    sub->add_option("--preset", o->preset, "Preset to start from (name or file)")
        ->capture_default_str();
    sub->add_option("--seed", o->seed, "Seed to start from")->capture_default_str();
    sub->add_option("--port", o->port, "Port (0: any free one)")->capture_default_str();
    sub->add_option("--host", o->host,
                    "Address to listen on; anything but 127.0.0.1 opens the page to "
                    "other machines")
        ->capture_default_str();
    sub->add_option("--out", o->out, "Folder the page's Save writes into")
        ->capture_default_str();
    o->threads.add_to(*sub);
    return [o] { return run(*o); };
}

}  // namespace pelage::renderer::cli
