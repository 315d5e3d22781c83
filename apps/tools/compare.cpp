#include "apps/tools/compare.h"

#include <sys/resource.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <random>

#include "pattern/statistics/spot_statistics.h"
#include "renderer/image/film.h"
#include "renderer/integrator/render.h"
#include "renderer/plugins/plugin_loader.h"
#include "renderer/scene/scene.h"
#include "sim/cells_io/cells_file.h"
#include "sim/core/input_error.h"
#include "sim/mesh/mesh_load.h"

namespace pelage::renderer {
namespace {

// CPU seconds: this process's (all threads), or this thread's. The machine may be shared;
// wall time also counts the time other jobs hold the cores, CPU time only ours.
double process_cpu_seconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
           1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}
double thread_cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// The objects with a "cells" file. (A pattern plugin that reads cells refuses an object
// without them, so every object a scene can render with one is among these.)
std::vector<size_t> patterned_objects(const SceneDesc &desc) {
    std::vector<size_t> out;
    for (size_t i = 0; i < desc.objects.size(); ++i)
        if (!desc.objects[i].cells.empty()) out.push_back(i);
    return out;
}

// The installed plugin called `name`, or null (the scene then fails to load, with the
// loader's message).
const PelageShaderPlugin *find_plugin(const PluginRegistry &plugins,
                                      const std::string &name) {
    const auto it = plugins.plugins().find(name);
    return it == plugins.plugins().end() ? nullptr : it->second.desc;
}

bool has_param(const PelageShaderPlugin *plugin, const char *name, PelageParamType type) {
    if (!plugin) return false;
    for (const PelageParamSpec *s = plugin->params; s && s->name; ++s)
        if (std::string(s->name) == name) return s->type == type;
    return false;
}

// Area-uniform points on the first patterned object: the hits every shader is timed on.
std::vector<PelageHit> sample_hits(const SceneDesc &desc, size_t object, size_t n,
                                   uint64_t seed) {
    const sim::TriangleMesh mesh = sim::load_mesh(desc.objects[object].mesh);
    std::vector<double> cdf;
    double sum = 0;
    for (sim::TriId t = 0; t < mesh.num_triangles(); ++t)
        cdf.push_back(sum += mesh.triangle_area(t));
    std::mt19937_64 rng(seed + 17);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<PelageHit> hits(n);
    for (PelageHit &h : hits) {
        const auto t = uint32_t(std::min<size_t>(
            std::upper_bound(cdf.begin(), cdf.end(), u(rng) * sum) - cdf.begin(),
            mesh.num_triangles() - 1));
        const double s = std::sqrt(u(rng)), r = u(rng);
        h = PelageHit{};
        h.object_id = uint32_t(object);
        h.primitive_id = t;
        h.b1 = float(s * (1 - r));
        h.b2 = float(s * r);
        const sim::Vec3d p = mesh.vertex(t, 0) * (1 - s) +
                             mesh.vertex(t, 1) * (s * (1 - r)) +
                             mesh.vertex(t, 2) * (s * r);
        const sim::Vec3d nrm = normalize(mesh.face_normal_unnormalized(t));
        for (int k = 0; k < 3; ++k) {
            h.p[k] = float(p[k]);
            h.n[k] = float(nrm[k]);
        }
        h.footprint = 1e-3f;
    }
    return hits;
}

// The mesh's corner UVs interpolated at each hit (for a shader that maps an image by UV).
void add_uvs(const sim::TriangleMesh &mesh, std::vector<PelageHit> &hits) {
    if (mesh.corner_uvs.size() != 3 * mesh.num_triangles()) return;
    for (PelageHit &h : hits) {
        const sim::Vec2d *uv = &mesh.corner_uvs[3 * size_t(h.primitive_id)];
        const double b0 = 1.0 - h.b1 - h.b2;
        h.uv[0] = float(b0 * uv[0].x + h.b1 * uv[1].x + h.b2 * uv[2].x);
        h.uv[1] = float(b0 * uv[0].y + h.b1 * uv[1].y + h.b2 * uv[2].y);
        h.has_uv = 1;
    }
}

float luminance(const std::array<float, 3> &c) {
    return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
}

// The noise value exceeded on `fraction` of the hits: the threshold that makes that
// fraction of the (area-uniform) surface spots. `slot`: the plugin's "noise" AOV.
float noise_quantile(const Scene &scene, size_t object,
                     const std::vector<PelageHit> &hits, double fraction, int slot) {
    const Material &mat = scene.materials()[object];
    std::vector<float> values;
    values.reserve(hits.size());
    for (const PelageHit &h : hits) {
        PelageShade sh = pelage_default_shade();
        mat.plugin->shade(mat.instance, &h, &sh);
        values.push_back(sh.aov[slot]);
    }
    if (values.empty()) return 0;
    const size_t k =
        std::min(values.size() - 1, size_t((1 - fraction) * double(values.size())));
    std::nth_element(values.begin(), values.begin() + k, values.end());
    return values[k];
}

}  // namespace

int aov_slot(const PelageShaderPlugin &plugin, const std::string &name) {
    if (plugin.aov_names)
        for (int k = 0; k < PELAGE_SHADER_AOV_SLOTS && plugin.aov_names[k]; ++k)
            if (plugin.aov_names[k] == name) return k;
    return -1;
}

BaselineModel baseline_model(const PelageShaderPlugin &plugin) {
    const auto is_float = [&](const char *n) {
        return has_param(&plugin, n, PELAGE_PARAM_FLOAT);
    };
    if (!has_param(&plugin, "spot_colour", PELAGE_PARAM_RGB) ||
        !has_param(&plugin, "base_colour", PELAGE_PARAM_RGB) || !is_float("frequency"))
        return BaselineModel::none;
    if (is_float("mean_points") && is_float("spot_fraction"))
        return BaselineModel::cellular;
    if (is_float("threshold") && aov_slot(plugin, "noise") >= 0)
        return BaselineModel::thresholded_noise;
    return BaselineModel::none;
}

bool maps_image_by_uv(const PelageShaderPlugin &plugin) {
    return has_param(&plugin, "file", PELAGE_PARAM_STRING) &&
           has_param(&plugin, "texels_per_unit", PELAGE_PARAM_FLOAT);
}

nlohmann::json matched_baseline_params(const PelageShaderPlugin &plugin,
                                       const std::string &cells_path) {
    const BaselineModel model = baseline_model(plugin);
    if (model == BaselineModel::none) return nlohmann::json::object();
    // The spots as the renderer shows them, on the surface the file carries.
    const pattern::mosaic::MosaicPattern pattern(cells_path);
    const pattern::statistics::SpotStatistics stats =
        pattern::statistics::measure_spot_statistics(pattern);
    const sim::CellsData &data = pattern.data();
    // Spot type: F when present, else the darkest; base: B when present, else the most
    // common other type.
    std::vector<size_t> count(data.types.size(), 0);
    for (uint8_t t : data.type) ++count[t];
    auto named = [&](const std::string &n) {
        for (size_t i = 0; i < data.types.size(); ++i)
            if (data.types[i].name == n) return int(i);
        return -1;
    };
    int spot = named("F"), base = named("B");
    for (size_t i = 0; i < data.types.size() && spot < 0; ++i)
        if (spot < 0 ||
            luminance(data.types[i].colour) < luminance(data.types[size_t(spot)].colour))
            spot = int(i);
    for (size_t i = 0; i < data.types.size() && base < 0; ++i)
        if (int(i) != spot && (base < 0 || count[i] > count[size_t(base)])) base = int(i);
    if (spot < 0) return nlohmann::json::object();
    if (base < 0) base = spot;
    const auto &sc = data.types[size_t(spot)].colour,
               &bc = data.types[size_t(base)].colour;
    const double area = std::max(data.area(), 1e-300);
    double fraction =
        data.num_cells() ? double(count[size_t(spot)]) / double(data.num_cells()) : 0.3;
    fraction = std::clamp(fraction, 0.01, 0.99);
    // Spots per unit area of the mosaic (at least one over the whole surface).
    const double spots_per_area = double(std::max<size_t>(stats.spots, 1)) / area;
    nlohmann::json p = {{"spot_colour", {sc[0], sc[1], sc[2]}},
                        {"base_colour", {bc[0], bc[1], bc[2]}}};
    if (model == BaselineModel::cellular) {
        // Section cells per unit area λ_A from the spots per unit area: a plane cuts a
        // Poisson–Voronoi tessellation of intensity λ into λ_A ≈ 1.4558 λ^(2/3) cells
        // per unit area (Okabe, Boots, Sugihara, Chiu 2000, Spatial Tessellations, §5.5),
        // and the plugin's intensity is mean_points · frequency³. Neighbouring spot cells
        // merge into one spot, so λ_A is a few times spots / fraction: the factor 2.85 is
        // fitted by eye (spot count and size) on the cheetah sphere's contact sheet.
        const double mean_points = 3, lambda_a = 2.85 * spots_per_area / fraction;
        const double lambda = std::pow(lambda_a / 1.4558, 1.5);
        p["frequency"] = std::cbrt(lambda / mean_points);
        p["mean_points"] = mean_points;
        p["spot_fraction"] = fraction;
    } else {
        // About 2.9 base-lattice squares of the surface per spot above the threshold:
        // fitted by eye on the cheetah sphere's contact sheet (fBm's blob count also
        // depends on the threshold, so it is an approximation).
        p["frequency"] = 1.71 * std::sqrt(spots_per_area);
        p["spot_fraction"] = fraction;  // compare_shaders turns it into a threshold
    }
    return p;
}

CompareResult compare_shaders(const SceneDesc &desc, const CompareOptions &options) {
    const std::vector<size_t> subjects = patterned_objects(desc);
    if (subjects.empty())
        throw InputError(desc.path, 0, "objects",
                         "no patterned object to compare: give an object a \"cells\" "
                         "file");
    const PluginRegistry plugins;
    const std::vector<PelageHit> hits =
        sample_hits(desc, subjects[0], options.lookups, options.seed);

    CompareResult result;
    result.reference = options.reference;
    result.width = desc.film.width;
    result.height = desc.film.height;
    // --- Every shader's scene first, so the renders below can alternate ---
    struct Prepared {
        std::unique_ptr<SceneDesc> desc;  // the scene refers to it: a stable address
        std::unique_ptr<Scene> scene;
    };
    std::vector<Prepared> prepared;
    const int repeats = std::max(options.repeats, 1);
    for (const std::string &shader : options.shaders) {
        const PelageShaderPlugin *plugin = find_plugin(plugins, shader);
        auto d = std::make_unique<SceneDesc>(desc);
        nlohmann::json params = nlohmann::json::object();  // the plugin's defaults
        if (plugin && options.match_baselines)
            params = matched_baseline_params(*plugin, desc.objects[subjects[0]].cells);
        const bool atlas =
            plugin && maps_image_by_uv(*plugin) && !options.texture_file.empty();
        if (atlas)
            params = {{"file", options.texture_file},
                      {"texels_per_unit", options.texels_per_unit}};
        // A spot fraction for a plugin without that parameter becomes the threshold
        // exceeded on that fraction of the surface by its "noise" AOV.
        double noise_fraction = -1;
        if (params.contains("spot_fraction") &&
            !has_param(plugin, "spot_fraction", PELAGE_PARAM_FLOAT)) {
            noise_fraction = params["spot_fraction"].get<double>();
            params.erase("spot_fraction");
        }
        for (size_t i : subjects) {
            MaterialDesc &m = d->objects[i].material;
            if (m.shader != shader) {
                m.params = params;
                if (atlas) d->objects[i].mesh = options.texture_mesh;
            }
            m.shader = shader;
        }
        if (noise_fraction >= 0 && desc.objects[subjects[0]].material.shader != shader) {
            // The threshold that makes the mosaic's spot fraction of the surface spots.
            const float threshold =
                noise_quantile(Scene(*d, plugins), subjects[0], hits, noise_fraction,
                               aov_slot(*plugin, "noise"));
            for (size_t i : subjects)
                if (desc.objects[i].material.shader != shader)
                    d->objects[i].material.params["threshold"] = threshold;
        }
        result.params[shader] = d->objects[subjects[0]].material.params;
        auto scene = std::make_unique<Scene>(*d, plugins);

        // --- Shading alone, on the same points for every shader ---
        // First untimed, which also warms what a plugin sets up lazily (the texture's
        // mip levels): the render below is then timed on equal terms for every shader.
        const Material &mat = scene->materials()[subjects[0]];
        std::vector<PelageHit> shader_hits = hits;
        if (atlas) add_uvs(sim::load_mesh(options.texture_mesh), shader_hits);
        float sink = 0;
        auto shade_all = [&] {
            for (const PelageHit &h : shader_hits) {
                PelageShade sh = pelage_default_shade();
                mat.plugin->shade(mat.instance, &h, &sh);
                sink += sh.albedo[0];
            }
        };
        shade_all();
        double ns = std::numeric_limits<double>::infinity();
        for (int k = 0; k < repeats; ++k) {
            const double t0 = thread_cpu_seconds();
            shade_all();
            ns = std::min(ns, 1e9 * (thread_cpu_seconds() - t0) /
                                  double(std::max<size_t>(hits.size(), 1)));
        }
        (void)sink;
        CompareRun run;
        run.shader = shader;
        run.ns_per_lookup = ns;
        result.runs.push_back(std::move(run));
        prepared.push_back({std::move(d), std::move(scene)});
    }

    // --- The renders: round after round, every shader once per round, the order
    // reversed every other round so that no shader always follows the same one ---
    RenderOptions ro;
    ro.seed = options.seed;
    for (int k = 0; k < repeats; ++k)
        for (size_t j = 0; j < prepared.size(); ++j) {
            const size_t i = k % 2 ? prepared.size() - 1 - j : j;
            CompareRun &run = result.runs[i];
            const double cpu0 = process_cpu_seconds();
            const RenderResult r = render(*prepared[i].scene, ro);
            const double cpu_seconds = process_cpu_seconds() - cpu0;
            run.cpu_seconds_each.push_back(cpu_seconds);
            run.cpu_seconds = k ? std::min(run.cpu_seconds, cpu_seconds) : cpu_seconds;
            run.seconds = k ? std::min(run.seconds, r.seconds) : r.seconds;
            if (k) continue;  // the same seed gives the same image every time
            const SceneDesc &d = *prepared[i].desc;
            const std::vector<float> px = r.film->resolve();
            run.rgb.resize(size_t(d.film.width) * d.film.height * 3);
            for (size_t p = 0; p < size_t(d.film.width) * d.film.height; ++p)
                for (int c = 0; c < 3; ++c)
                    run.rgb[3 * p + c] = px[p * Film::num_channels + c];
        }
    return result;
}

DriftResult measure_pattern_drift(const SceneDesc &desc, const CompareOptions &options) {
    DriftResult result;
    bool found = false;
    for (size_t i : patterned_objects(desc))
        if (!desc.objects[i].deform.empty() || desc.objects[i].clip) {
            result.object = i;
            found = true;
            break;
        }
    if (!found)
        throw InputError(desc.path, 0, "objects",
                         "--deform needs a patterned object with a \"deform\" mesh (a "
                         "second pose with the same topology) or an animation clip");
    const size_t obj = result.object;
    const ObjectDesc &od = desc.objects[obj];
    // The poses measured: the last "deform" mesh, or a clip at eight times spread over
    // its length (its first frame and seven more).
    const int clip_poses = 8;
    const int num_poses = od.clip ? clip_poses : 1;
    result.pose = od.clip ? "clip \"" + od.clip->name + "\" at " +
                                std::to_string(clip_poses) + " times"
                          : od.deform.back();
    auto set_pose = [&](ObjectDesc &o, int k) {
        if (o.clip) {
            o.clip_seconds = o.clip->duration * double(k) / double(clip_poses);
        } else {
            o.deform_mesh = od.deform.back();
            o.deform_weight = 1;
        }
    };
    const PluginRegistry plugins;
    std::vector<PelageHit> hits = sample_hits(desc, obj, options.lookups, options.seed);

    // Each hit's position on a scene's mesh (object space), as the renderer would pass
    // it.
    auto place = [&](const Scene &scene, std::vector<PelageHit> &hs) {
        const MeshData &m = *scene.geometry().objects()[obj].mesh;
        for (PelageHit &h : hs) {
            const uint32_t *t = &m.triangles[3 * size_t(h.primitive_id)];
            const float b0 = 1 - h.b1 - h.b2;
            for (int k = 0; k < 3; ++k)
                h.p[k] = b0 * m.object_positions[3 * t[0] + k] +
                         h.b1 * m.object_positions[3 * t[1] + k] +
                         h.b2 * m.object_positions[3 * t[2] + k];
        }
    };
    for (const std::string &shader : options.shaders) {
        SceneDesc d = desc;
        for (size_t i : patterned_objects(desc)) {
            MaterialDesc &m = d.objects[i].material;
            if (m.shader != shader) m.params = nlohmann::json::object();
            m.shader = shader;
        }
        SceneDesc rest_desc = d;
        rest_desc.objects[obj].deform_mesh.clear();
        rest_desc.objects[obj].deform_weight = 0;
        rest_desc.objects[obj].clip.reset();
        const Scene rest(rest_desc, plugins);
        std::vector<PelageHit> at_rest = hits;
        place(rest, at_rest);
        const Material &mr = rest.materials()[obj];
        std::vector<PelageShade> rest_shade(hits.size());
        for (size_t i = 0; i < hits.size(); ++i) {
            rest_shade[i] = PelageShade{};
            mr.plugin->shade(mr.instance, &at_rest[i], &rest_shade[i]);
        }
        DriftRun run{shader, 0, 0, hits.size() * size_t(num_poses)};
        double sum = 0;
        for (int k = 0; k < num_poses; ++k) {
            set_pose(d.objects[obj], k);
            const Scene pose(d, plugins);
            std::vector<PelageHit> at_pose = hits;
            place(pose, at_pose);
            const Material &mp = pose.materials()[obj];
            for (size_t i = 0; i < hits.size(); ++i) {
                PelageShade b{};
                mp.plugin->shade(mp.instance, &at_pose[i], &b);
                double d3 = 0;
                for (int c = 0; c < 3; ++c)
                    d3 += std::abs(double(rest_shade[i].albedo[c]) - b.albedo[c]);
                d3 /= 3;
                sum += d3;
                run.max = std::max(run.max, d3);
            }
        }
        run.mean = run.points == 0 ? 0 : sum / double(run.points);
        result.runs.push_back(run);
    }
    return result;
}

nlohmann::json DriftResult::report() const {
    nlohmann::json drift = nlohmann::json::object();
    for (const DriftRun &r : runs)
        drift[r.shader] = {{"mean", r.mean}, {"max", r.max}, {"points", r.points}};
    return {{"object", object}, {"pose", pose}, {"pattern_drift", drift}};
}

nlohmann::json CompareResult::report() const {
    nlohmann::json shaders = nlohmann::json::object();
    const CompareRun *cm = nullptr;  // the reference's run
    for (const CompareRun &r : runs) {
        shaders[r.shader] = {{"seconds", r.seconds},
                             {"cpu_seconds", r.cpu_seconds},
                             {"cpu_seconds_each", r.cpu_seconds_each},
                             {"ns_per_lookup", r.ns_per_lookup}};
        if (r.shader == reference) cm = &r;
    }
    nlohmann::json ratios = nlohmann::json::object(),
                   lookup_ratios = nlohmann::json::object(),
                   ratio_rounds = nlohmann::json::object();
    if (cm)
        for (const CompareRun &r : runs) {
            if (&r == cm) continue;
            // CPU time: on a shared machine it is what the render cost us (wall:
            // seconds).
            ratios[reference + "_vs_" + r.shader] =
                r.cpu_seconds > 0 ? cm->cpu_seconds / r.cpu_seconds : 0.0;
            lookup_ratios[reference + "_vs_" + r.shader] =
                r.ns_per_lookup > 0 ? cm->ns_per_lookup / r.ns_per_lookup : 0.0;
            // Round by round (the two renders of a round ran back to back): how far a
            // ratio moves between rounds is the machine's noise, which a single figure
            // hides. The ratio of the minima always lies within [min, max] of these.
            std::vector<double> paired;
            for (size_t k = 0;
                 k < std::min(cm->cpu_seconds_each.size(), r.cpu_seconds_each.size());
                 ++k)
                if (r.cpu_seconds_each[k] > 0)
                    paired.push_back(cm->cpu_seconds_each[k] / r.cpu_seconds_each[k]);
            if (!paired.empty()) {
                std::sort(paired.begin(), paired.end());
                const size_t n = paired.size();
                const double median =
                    n % 2 ? paired[n / 2] : 0.5 * (paired[n / 2 - 1] + paired[n / 2]);
                ratio_rounds[reference + "_vs_" + r.shader] = {
                    {"min", paired.front()}, {"median", median}, {"max", paired.back()}};
            }
        }
    return {{"width", width},
            {"height", height},
            {"repeats", runs.empty() ? 0 : runs[0].cpu_seconds_each.size()},
            {"shaders", shaders},
            {"ratios", ratios},
            {"ratio_rounds", ratio_rounds},
            {"lookup_ratios", lookup_ratios},
            {"params", params}};
}

}  // namespace pelage::renderer
