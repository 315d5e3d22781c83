#!/usr/bin/env python3
"""Rewrites the generated tables of docs/performance.md and docs/validation.md from the
JSON files in docs/data/ (written by docs/tools/run_benchmarks.sh), and the scene file's
reference tables in docs/guide/scene-format.md and fur.md from `pelage fields` (the table the
parser reads by, renderer/scene_file/scene_fields.cpp; $PELAGE or build/bin/pelage).

A generated region is everything between
    <!-- BEGIN generated: NAME -->
    <!-- END generated: NAME -->
on lines of their own; NAME selects one of the TABLES below. Text outside the markers is
never touched, and running the script twice changes nothing the second time.

Usage:
    python3 docs/tools/make_tables.py           rewrite the files that are out of date
    python3 docs/tools/make_tables.py --check   exit 1 (and name them) if any file is out of date

Python 3 standard library only.
"""
import argparse
import json
import os
import re
import statistics
import sys

DOCS = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(DOCS, "data")
FILES = ["performance.md", "validation.md", "guide/presets.md", "guide/growth-and-control.md",
         "guide/explore.md", "guide/scene-format.md", "guide/fur.md"]
PELAGE = os.environ.get("PELAGE", os.path.join(os.path.dirname(DOCS), "build", "bin", "pelage"))
MARKER = re.compile(
    r"(<!-- BEGIN generated: (?P<name>[\w.-]+) -->\n)(?P<body>.*?)(<!-- END generated: (?P=name) -->)",
    re.S)

_cache = {}


def data(name):
    """docs/data/NAME.json, parsed once."""
    if name not in _cache:
        path = os.path.join(DATA, name + ".json")
        try:
            with open(path, encoding="utf-8") as f:
                _cache[name] = json.load(f)
        except (OSError, ValueError) as e:
            sys.exit(f"make_tables: {path}: {e}")
    return _cache[name]


def table(header, rows, align=None):
    """A Markdown table; align is a string of 'l'/'r' per column (default: l, then r)."""
    align = align or "l" + "r" * (len(header) - 1)
    rule = ["---:" if a == "r" else "---" for a in align]
    lines = ["| " + " | ".join(header) + " |", "| " + " | ".join(rule) + " |"]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines) + "\n"


def mesh_name(path):
    if path.startswith("procedural:"):
        return path[len("procedural:"):].replace(":", " ").replace("x", "×")
    base = os.path.basename(path)
    return base[:-4] if base.endswith((".off", ".obj")) else path


def num(x, digits=3):
    """A number with `digits` significant digits (whole numbers from 100 up), thousands
    separated by spaces."""
    if x is None:
        return "—"
    if x == 0:
        return "0"
    if abs(x) >= 100 or (isinstance(x, int)):
        return f"{x:,.0f}".replace(",", " ")
    s = f"{x:.{digits}g}"
    if "e" in s:
        mant, exp = s.split("e")
        return f"{mant}·10^{int(exp)}"
    return s


def pct(x, digits=1):
    return f"{100 * x:.{digits}f} %"


def signed_pct(x):
    return f"{100 * x:+.1f} %"


def millions(x):
    return f"{x / 1e6:.2f} M"


# --- performance.md -------------------------------------------------------------------

def t_machine():
    m, r = data("machine"), data("run_times")
    return table(["", ""], [
        ["CPU", m["cpu"]],
        ["logical CPUs", m["logical_cpus"]],
        ["system", m["system"]],
        ["pelage", m["pelage"]],
        ["wall time of every command in `run_benchmarks.sh`", f"{r['total_wall_seconds']} s"],
    ], "ll")


def t_crps():
    d = data("bench_crps")
    rows = [[mesh_name(r["mesh"]), num(r["triangles"]), num(r["ns_per_triangle"]),
             num(r["topology_seconds"] * 1e3), num(r["crps_seconds"] * 1e3),
             millions(r["maps_per_second"]) + "/s", num(r["unfold_ns"] / 1e3),
             num(r["unfold_triangles_mean"])] for r in d["runs"]]
    out = table(["mesh", "triangles", "build ns / triangle", "topology ms", "CRPS ms",
                 "neighbour maps", "unfold µs", "triangles unfolded"], rows)
    return out + (f"\nBuild time per triangle, largest mesh over smallest: "
                  f"**{d['ns_per_triangle_ratio']:.2f}** (`ns_per_triangle_ratio`; "
                  f"{d['threads']} thread).\n")


def t_sim():
    d = data("bench_sim")
    rows = [[num(r["initial_cells"]), r["relax"], num(r["final_cells"]),
             f"{r['spot_fraction']:.4f}", num(r["seconds"]), num(r["seconds_simulation"]),
             num(r["ns_per_cell_step"]), num(r["ns_per_cell_step_relax"])]
            for r in d["runs"]]
    out = table(["initial cells", "relaxation", "final cells", "spot fraction",
                 "seconds (total)", "simulation phase s", "ns / cell-step",
                 "ns / cell-step, relaxation only"], rows)
    out += (f"\n* Local over global relaxation, simulation phase (`local_speedup`): "
            f"**{d['local_speedup']:.2f}×**; including the initial relaxation both share "
            f"(`local_speedup_total`): {d['local_speedup_total']:.2f}×.\n"
            f"* Spot fraction, local minus global (`spot_fraction_difference`): "
            f"{d['spot_fraction_difference']}.\n"
            f"* Cost per cell-step, largest over smallest run (`cost_per_cell_step_ratio_*`): "
            f"global {d['cost_per_cell_step_ratio_global']:.2f}, local "
            f"{d['cost_per_cell_step_ratio_local']:.2f}; relaxation only "
            f"(`relax_cost_per_cell_step_ratio_*`): global "
            f"{d['relax_cost_per_cell_step_ratio_global']:.2f}, local "
            f"{d['relax_cost_per_cell_step_ratio_local']:.2f}.\n")
    if "large" in d:
        g = d["large"]
        out += (f"* Large run on {mesh_name(g['mesh'])} ({num(g['triangles'])} triangles): "
                f"{num(g['initial_cells'])} → {num(g['final_cells'])} cells, "
                f"{num(g['divisions'])} divisions, {g['relax_steps']} relaxation steps, "
                f"{num(g['seconds'])} s ({num(g['seconds_initial'])} s of it the initial "
                f"relaxation), peak RSS {g['peak_rss_mb']:.0f} MB.\n")
    return out


def t_sim_mclone():
    d = data("bench_sim")["mclone"]
    rows = [[r["relax"], num(r["final_cells"]), num(r["cell_steps"]),
             f"{r['cpu_seconds']:.2f}", num(r["ns_per_cell_step"]),
             num(r["interacting_pairs"] / max(r["cell_steps"], 1)),
             f"{1e9 * r['seconds_force_sum'] / max(r['interacting_pairs'], 1):.2f}",
             pct(r["seconds_force_sum"] / r["seconds"], 0), f"{r['speedup']:.1f}×"]
            for r in d["runs"]]
    return (table(["relaxation", "final cells", "cell-steps", "CPU s", "ns / cell-step",
                   "pairs / cell-step", "force sum ns / pair", "force sum share",
                   "MClone CPU s / pelage CPU s"], rows) +
            f"\nWalter's cheetah-like configuration (thesis Fig. 3.10 with Queiroz's w_d: "
            f"ρ 18, w_r 2, {num(d['initial_cells'])} initial cells, 15 days, division times "
            "8/60, α_FF 0.8, α_BB 0.5, w_d 0.067, w_a 0, P(F) 0.15, Poisson) on "
            f"{mesh_name(d['mesh'])}, the whole `pelage sim` run from loading the mesh, "
            f"fastest of the repeats; MClone takes {d['mclone_cpu_seconds']} CPU s with "
            "global relaxation on the same machine (`mclone`).\n")


def t_sim_density():
    d = data("bench_sim")
    runs = d["density"] + ([d["density_coarse"]] if "density_coarse" in d else [])
    rows = [[str(r["subdivisions"]) if r["subdivisions"] >= 0 else "low-poly copy",
             num(r["triangles"]), num(r["simulation_triangles"]),
             num(r["final_cells"]), f"{r['cells_per_triangle']:.1f}", num(r["seconds"]),
             num(r["ns_per_cell_step"]), num(r["peak_rss_mb"]),
             f"{r['peak_rss_kb_per_cell']:.1f}"]
            for r in runs]
    coarse = ""
    if "density_coarse" in d:
        coarse = (" The low-poly copy is the mesh collapsed to about 110 of the input run's "
                  "final cells per triangle (more than 128 are split at the edge "
                  "midpoints): ns per cell-step over the input's "
                  f"**{d['density_coarse_ns_per_cell_step_ratio']:.2f}×** "
                  "(`density_coarse_ns_per_cell_step_ratio`).")
    return (table(["midpoint splits", "triangles", "simulated on", "final cells",
                   "cells / simulated triangle", "seconds", "ns / cell-step", "peak MB",
                   "peak KB / cell"], rows) +
            f"\n`{d['density_preset']}` on {mesh_name(d['density_mesh'])}, the same surface "
            "split at its edge midpoints, each run a separate `pelage sim` process "
            f"({d['threads']} thread). Finest over coarsest: ns per cell-step "
            f"**{d['density_ns_per_cell_step_ratio']:.2f}×** "
            f"(`density_ns_per_cell_step_ratio`), peak memory per cell "
            f"**{d['density_peak_rss_ratio']:.2f}×** (`density_peak_rss_ratio`)." + coarse +
            "\n")


def t_sim_neighbours():
    d = data("bench_sim")
    pct = lambda x: f"{x:.2f} %"
    rows = []
    for r in d["neighbours"]:
        c, f = r["checked"], r["first_path"]
        rows.append([mesh_name(r["mesh"]), num(r["pairs"]), str(c["through_folds"]),
                     pct(c["missed_percent"]), pct(100 * c["mean_error_r"]),
                     pct(100 * c["worst_error_r"]), str(f["through_folds"]),
                     pct(100 * f["worst_error_r"])])
    r0 = d["neighbours"][0]
    return (table(["mesh", "pairs within r", "checked: through folds", "missed",
                   "mean error (of r)", "worst error (of r)", "first-path: through folds",
                   "worst error (of r)"], rows) +
            f"\n{num(r0['cells'])} area-uniform cells, w_r 3.3, the neighbours of "
            f"{r0['queries']} of them per mesh (`pelage bench sim`, key `neighbours`).\n")


def t_default_job():
    s, st = data("sim_cow_giraffe"), data("stats_cow_giraffe")
    s2 = data("sim_cow_giraffe_2threads")
    by_type = ", ".join(f"{k} {num(v)}" for k, v in sorted(s["cells_by_type"].items()))
    return table(["", ""], [
        ["command", f"`pelage sim --mesh scenes/meshes/cow.off --preset {s['preset']} "
                    f"--seed {s['seed']}`"],
        ["triangles", num(s["triangles"])],
        ["cells", f"{num(s['initial_cells'])} → {num(s['final_cells'])} ({by_type})"],
        ["divisions, relaxation steps", f"{num(s['divisions'])}, {num(s['relax_steps'])} "
                                        f"(+{s['initial_relax_steps']} initial, {s['relax']})"],
        ["seconds (one thread)", f"{num(s['seconds'])} ({num(s['seconds_initial'])} initial relaxation)"],
        ["seconds (two threads)", f"{num(s2['seconds'])} ({num(s2['seconds_initial'])} initial relaxation)"],
        ["where the time goes (one thread)",
         f"neighbourhoods {num(s['seconds_neighbourhoods'])} s, force sum "
         f"{num(s['seconds_force_sum'])} s ({pct(s['seconds_force_sum'] / s['seconds'], 0)}), "
         f"the rest {num(s['seconds'] - s['seconds_neighbourhoods'] - s['seconds_force_sum'])} s"],
        ["interacting pairs", f"{num(s['interacting_pairs'])}, "
                              f"{num(s['interacting_pairs'] / s['cell_steps'])} per cell-step, "
                              f"{1e9 * s['seconds_force_sum'] / s['interacting_pairs']:.2f} ns each "
                              "in the force sum"],
        ["spot fraction, spots, largest spot", f"{st['spot_fraction']:.3f}, {st['spot_count']}, "
                                               f"{num(st['largest_spot_cells'])} cells"],
        ["spot fraction by area", f"{st['spot_fraction_by_area']:.3f} "
                                  f"({num(st['area_samples'])} surface points)"],
    ], "ll")


def lookup_runs():
    return data("bench_lookup")["runs"]


def t_lookup():
    rows = [[mesh_name(r["mesh"]), num(r["triangles"]), num(r["ns_per_lookup"]),
             num(r["ns_per_lookup_f1_only"]), num(r["ns_per_lookup_coherent"]),
             num(r["ns_per_lookup_banded_coherent"]),
             f"{num(r['ns_per_lookup_banded_walk_reuse'])} ({pct(r['walk_reused'], 0)})",
             num(r["ns_per_lookup_lod"]), num(r["ns_per_lookup_exhaustive"]),
             f"{r['index_megabytes']:.1f}", num(r["build_seconds"])]
            for r in lookup_runs()]
    d = data("bench_lookup")
    cells = lookup_runs()[0]["cells"]
    return (table(["mesh", "triangles", "F1+F2 random", "F1 random", "F1+F2 coherent",
                   "banded coherent", "banded walk, reuse (reused)", "level of detail",
                   "exhaustive", "index MB", "index build s"], rows) +
            f"\nns per lookup, thread CPU time; {num(cells)} random cells per surface, "
            f"{num(d['queries'])} queries.\n")


def t_lookup_lanes():
    rows = [[mesh_name(r["mesh"]), r["lanes"], num(r["ns_per_lookup"]),
             num(r["ns_per_lookup_four_lanes"]),
             f"{r['ns_per_lookup_four_lanes'] / r['ns_per_lookup']:.2f}",
             "yes" if r["lanes_agree"] else "**no**"] for r in lookup_runs()]
    return table(["mesh", "lanes used", "ns, widest scan", "ns, four lanes", "ratio",
                  "same results"], rows)


def t_lookup_density():
    d = data("bench_lookup")
    rows = [[str(r["subdivisions"]), num(r["triangles"]), num(r["cells"]),
             num(r["ns_per_lookup_f1_only"]), f"{r['ns_ratio']:.2f}", num(r["build_seconds"]),
             f"{r['build_ratio']:.2f}", num(r["index_megabytes"]),
             num(r["geodesic_megabytes"])] for r in d["density"]]
    return (table(["midpoint splits", "triangles", "cells", "F1 random, ns", "× first",
                   "index build s", "× first", "index MB", "geodesic windows while building, MB"],
                  rows) + f"\n{mesh_name(d['density_mesh'])}, the same surface split at its edge "
            "midpoints; thread CPU time for lookups, wall time for the build (all cores).\n")


def t_render():
    d = data("bench_render")
    return table(["quantity", "value"], [
        ["scene, size", f"{os.path.basename(d['scene'])}, {d['width']}×{d['height']}, "
                        f"{d['spp']} spp, {num(d['triangles'])} triangles"],
        ["rays (camera + secondary + shadow)", f"{millions(d['rays'])} ({millions(d['camera_rays'])} + "
                                               f"{millions(d['secondary_rays'])} + {millions(d['shadow_rays'])})"],
        ["camera packet width", d["camera_packet_width"]],
        ["path tracer / raw Embree `rtcIntersect1`, per CPU second (`ratio_cpu`)", f"**{d['ratio_cpu']:.2f}**"],
        ["the same, wall clock (`ratio`)", f"{d['ratio']:.2f}"],
        ["path tracer / Embree doing the same calls (`ratio_same_calls`)", f"{d['ratio_same_calls']:.2f}"],
        [f"1-thread time over {d['threads']}-thread time, wall clock (`thread_scaling`)", f"{d['thread_scaling']:.2f}"],
        ["path tracer, 1 thread", f"{millions(d['path_tracer_rays_per_second_1_thread'])} rays/s"],
        ["plugin time, sampled against timed on every call "
         "(`plugin_seconds_extrapolation_error`)", signed_pct(d["plugin_seconds_extrapolation_error"])],
    ], "ll")


def t_compare():
    d = data("compare_sphere_cheetah")
    sh = d["shaders"]
    order = ["clonal_mosaic", "worley", "perlin", "texture", "diffuse"]
    rows = []
    for name in [n for n in order if n in sh] + sorted(set(sh) - set(order)):
        key = "clonal_mosaic_vs_" + name
        ratio = d["ratio_rounds"].get(key)
        rows.append([f"`{name}`", num(sh[name]["cpu_seconds"]), num(sh[name]["ns_per_lookup"]),
                     "—" if name == "clonal_mosaic" else f"{sh['clonal_mosaic']['cpu_seconds'] / sh[name]['cpu_seconds']:.2f}",
                     "—" if not ratio else f"{ratio['median']:.2f} ({ratio['min']:.2f}–{ratio['max']:.2f})",
                     "—" if name == "clonal_mosaic" else f"{d['lookup_ratios'][key]:.3g}"])
    return (table(["shader", "render CPU s (least of the repetitions)", "shade ns / lookup",
                   "CM / shader, render", "CM / shader, per repetition: median (range)",
                   "CM / shader, lookup"], rows) +
            f"\n{d['width']}×{d['height']} pixels, each shader rendered {d['repeats']} times, "
            f"alternating.\n")


def t_hair():
    d = data("bench_hair")
    return table(["call", "ns"], [[k, num(d[k + "_ns"])] for k in
                                  ["eval", "pdf", "sample", "construct"]])


def t_fur():
    d = data("bench_fur")
    rows = [[num(r["strands"]), num(r["grow_seconds"]), num(r["embree_seconds"]),
             num(r["scene_cpu_seconds"]), num(r["strands_per_second"]),
             f"{r['peak_rss_mb']:.0f} MB",
             # Per million strands, from the same run (older JSON lacks the keys).
             f"{r['peak_rss_mb'] / (r['strands'] * 1e-6):.0f} MB",
             f"{r['scene_cpu_seconds'] / (r['strands'] * 1e-6):.1f} s",
             millions(r["rays_per_second"]),
             millions(r["rays_per_second_no_fur"]), f"{r['ratio']:.2f}"] for r in d["runs"]]
    r0 = d["runs"][0]
    return (table(["strands", "grow s", "Embree build s", "scene CPU s", "strands / s",
                   "peak RSS", "peak RSS / M strands", "scene CPU s / M strands",
                   "rays/s, fur", "rays/s, bare", "ratio"], rows) +
            f"\n{r0['width']}×{r0['height']}, {r0['spp']} spp, {r0['curve']} curves, "
            f"{r0['segments']} segments per strand.\n")


def t_export():
    d = data("bench_export")
    return (table(["strands", "control points", "stage", "set-up s", "export s",
                   "s / M strands", "MB / M strands"],
                  [[num(d["strands"]), num(d["points"]), f"{d['bytes'] / 1e6:.0f} MB",
                    num(d["setup_seconds"]), num(d["export_seconds"]),
                    f"{d['seconds_per_million_strands']:.2f}",
                    f"{d['mb_per_million_strands']:.0f}"]]) +
            f"\n`pelage bench export {d['scene']} --density-scale {d['density_scale']:g}"
            f" --threads {d['threads']}`: the median of {d['repeats']} exports.\n")


def t_fur_colour():
    d = data("fur_colour")
    rgb = lambda c: "(" + ", ".join(f"{x:.3f}" for x in c) + ")"
    rows = [[f"`{p['preset']}`", t["type"], rgb(t["bare"]), rgb(t["fur"]),
             f"{t['luminance_ratio']:.2f}", f"{t['rg_ratio']:.2f}", f"{t['bg_ratio']:.2f}",
             f"{num(t['bare_pixels'])} / {num(t['fur_pixels'])}"]
            for p in d["presets"] for t in p["types"]]
    return (table(["preset", "type", "bare (linear RGB)", "furry", "luminance ratio",
                   "R/G ratio", "B/G ratio", "pixels bare / furry"], rows, "llllrrrr") +
            f"\n`pelage bench fur-colour` on `{d['mesh']}`, {d['res']}, {d['spp']} spp, "
            f"seed {d['seed']}: `pelage look` bare and `--fur`, each type's mean over the "
            f"pixels its Cryptomatte covers fully. Targets: luminance ratio in [0.75, 1.33], "
            f"R/G and B/G within 15 % of 1.\n")


def t_fur_comb():
    d = data("fur_comb")
    rows = [[name, num(d[key]["samples"]), f"{d[key]['median_deg']:.2f}°",
             f"{d[key]['p95_deg']:.2f}°", f"{d[key]['p99_deg']:.1f}°", target]
            for name, key, target in [
                ("strand to the field at its root", "strand_to_field", "median ≤ 5°"),
                ("strand to its nearest roots' strands", "strand_to_neighbours",
                 "p95 ≤ 10°"),
                ("the field to its own at those roots", "field_to_neighbours", "")]]
    keys = ", ".join(f"`{k}` {v}" for k, v in d["fur_keys"].items())
    return (table(["angle, in each root's tangent plane", "pairs", "median", "p95", "p99",
                   "target"], rows, "lrrrrl") +
            f"\n`pelage bench fur-comb` on `{d['mesh']}`, preset `{d['preset']}`'s field, "
            f"{num(d['strands'])} strands, fur keys {keys} (those of `pelage look --fur` "
            f"with a field), comb smoothing {d['comb_smoothing']}.\n")


def t_fur_slab():
    d = data("fur_colour")
    rgb = lambda c: "(" + ", ".join(f"{x:.3f}" for x in c) + ")"
    rows = [[rgb(r["requested"]), f"{r['depth']:g}", rgb(r["measured"]),
             ", ".join(f"{100 * e:+.1f} %" for e in r["relative_error"])] for r in d["slab"]]
    return (table(["requested colour", "coat depth", "slab's albedo", "error per channel"],
                  rows, "lrll") +
            f"\nβ_n = {d['beta_n']:.2g}; each slab on a skin of the requested colour, its "
            f"albedo the Gauss–Legendre mean of three views, {d['slab_spp']} spp over 24 × 24 "
            f"pixels each.\n")


def t_noise():
    rows = []
    for name in ["bench_noise", "bench_noise_fur"]:
        d = data(name)
        for r in d["by_spp"]:
            rows.append([f"`{os.path.basename(d['scene'])}`", r["spp"], num(r["cpu_seconds"]),
                         f"{r['rmse']:.4f}", f"{r['rmse'] / d['reference_mean']:.3f}",
                         f"{r['time_mse']:.2e}", f"{r['fireflies']:g}"])
    d = data("bench_noise")
    f = data("bench_noise_fur")
    return (table(["scene", "spp", "CPU s", "RMSE", "RMSE / mean", "CPU s × MSE",
                   "fireflies"], rows) +
            f"\n{d['width']}×{d['height']} pixels; errors over the objects' pixels against "
            f"{d['reference']['spp']}-spp (`{os.path.basename(d['scene'])}`) and "
            f"{f['reference']['spp']}-spp (`{os.path.basename(f['scene'])}`) references; "
            f"means over {len([r for r in d['runs'] if r['spp'] == d['runs'][0]['spp']])} "
            f"seeds.\n")


def t_denoise():
    rows = []
    for name, target in [("bench_denoise", 8), ("bench_denoise_fur", 10)]:
        d = data(name)
        for r in d["by_spp"]:
            dn = r["denoised"]
            runs = [x for x in d["runs"] if x["spp"] == r["spp"] and "type_edges" in x["denoised"]]
            halo = max((x["denoised"]["type_edges"]["halo_pixels"] for x in runs), default=None)
            bias = max((x["denoised"]["type_edges"]["max_bias"] for x in runs), default=None)
            nhalo = max((x["noisy_type_edges"]["halo_pixels"] for x in runs), default=None)
            nbias = max((x["noisy_type_edges"]["max_bias"] for x in runs), default=None)
            rows.append([f"`{os.path.basename(d['scene'])}`", r["spp"], f"{r['mse']:.2e}",
                         f"{dn['mse']:.2e}", f"{dn['mse_ratio']:.1f}× (≥ {target}×)",
                         "–" if halo is None else f"{halo} px ({nhalo})",
                         "–" if bias is None else f"{100 * bias:.1f} % ({100 * nbias:.1f} %)",
                         num(dn["cpu_seconds"]), f"{r['time_mse']:.2e}", f"{dn['time_mse']:.2e}"])
    by = {r["spp"]: r for r in data("bench_denoise")["by_spp"]}
    flicker = ""
    if 16 in by and 256 in by and "flicker" in by[16]["denoised"]:
        flicker = (f" Flicker (a pixel's variance across seeds, as between frames of a "
                   f"turntable's static pixels): denoised 16 spp {by[16]['denoised']['flicker']:.2e} "
                   f"against noisy 256 spp {by[256]['flicker']:.2e} (target: no higher).")
    c = data("denoise_1080")
    render = c["seconds"]
    d = data("bench_denoise")
    return (table(["scene", "spp", "MSE noisy", "MSE denoised", "gain (target)", "halo",
                   "largest type bias", "denoise CPU s", "CPU s × MSE noisy",
                   "… denoised"], rows) +
            f"\n{d['width']}×{d['height']} pixels, the references and pixels of the noise "
            f"table above; means over the seeds (halo and bias: the worst seed). Halo: the "
            f"widest band along an edge between two cell types whose mean is more than 2 % "
            f"off the reference's; bias: a type's mean at least 4 pixels from an edge "
            f"against the reference's; in parentheses the noisy image's own, which is "
            f"the measure's noise floor (8 px is the widest band measured). At 1920×1080 the denoiser took "
            f"{num(c['denoise_seconds'])} s after a {num(render)} s 64-spp render of the bare "
            f"cow ({100 * c['denoise_seconds'] / render:.1f} % of it; target ≤ 10 %).{flicker}\n")


def t_fur_regularisation():
    reg = data("bench_noise_fur")
    exact = data("bench_noise_fur_unregularised")
    ref = reg["reference_mean_rgb"]
    rows = []
    for label, d in [("0 (off)", exact), ("0.4 (default)", reg)]:
        for r in d["by_spp"]:
            rel = r["rmse"] / d["reference_mean"]
            rows.append([label, r["spp"], num(r["cpu_seconds"]), f"{rel:.3f}",
                         f"{r['cpu_seconds'] * rel * rel:.2f}",
                         f"{r['max_error_over_mean']:.1f}",
                         ", ".join(signed_pct(m / c - 1) for m, c in zip(r["mean_rgb"], ref))])
    return (table(["`fur_bounce_roughness`", "spp", "CPU s", "RMSE / mean",
                   "CPU s × (RMSE / mean)²", "worst pixel / mean",
                   "mean R, G, B against the reference"], rows, "lrrrrrl") +
            f"\n`pelage bench noise` on `{os.path.basename(reg['scene'])}` and "
            f"`{os.path.basename(exact['scene'])}` (the same scene at 0), "
            f"{reg['width']}×{reg['height']}, {reg['object_pixels']} object pixels, means over "
            f"2 seeds (worst pixel: over both); both against the "
            f"{reg['reference']['spp']}-spp reference rendered at 0 (mean "
            f"{reg['reference_mean']:.4f}), whose own error is in every RMSE: about "
            f"1/{round(reg['reference']['spp'] / 64)} of the 64-spp MSE. Targets (the fur issue): CPU s × "
            f"(RMSE / mean)² ≤ 0.25 at 64 spp, worst pixel ≤ 5 × the mean, means within 3 %.\n")


def t_fur_glitter():
    f = data("bench_noise_fur_far")
    w = data("bench_noise_fur_far_widened")
    ref = f["reference_mean_rgb"]
    rows = []
    for label, d in [("fibres", f), ("widened to 1 px", w)]:
        for r in d["by_spp"]:
            rows.append([label, r["spp"], num(r["cpu_seconds"]), f"{r['rmse']:.4f}",
                         f"{r['time_mse']:.2e}",
                         ", ".join(signed_pct(m / c - 1) for m, c in zip(r["mean_rgb"], ref))])
    equal = [r for r in f["by_spp"] if r["spp"] == 64]
    note = ""
    if equal:
        w16 = next(r for r in w["by_spp"] if r["spp"] == 16)
        note = (f" At about equal time the fibres at 64 spp ({num(equal[0]['cpu_seconds'])} CPU s) "
                f"have {w16['rmse'] / equal[0]['rmse']:.2f} times less error than the "
                f"widened strands at 16 ({num(w16['cpu_seconds'])} CPU s).")
    return (table(["strands", "spp", "CPU s", "RMSE", "CPU s × MSE",
                   "mean R, G, B against the reference"], rows, "lrrrrl") +
            f"\n`pelage bench noise` on `{os.path.basename(f['scene'])}` and "
            f"`{os.path.basename(w['scene'])}`, {f['width']}×{f['height']}, "
            f"{f['object_pixels']} object pixels, means over 2 seeds; both measured against "
            f"the fibres' {f['reference']['spp']}-spp reference (mean "
            f"{f['reference_mean']:.3f}). Targets: 3 times less noise at equal time, "
            f"converged mean within 2 %.{note}\n")


def t_cycles_fur():
    d = data("cycles_fur")
    rows = []
    for case in ["bare", "fur"]:
        c = d["cases"].get(case)
        if not c:
            continue
        for r in c["by_spp"]:
            p, y = r["pelage"], r["cycles"]
            rows.append([case, r["spp"], f"{num(p['render_cpu_seconds'])} / {num(y['render_cpu_seconds'])}",
                         f"{p['relative_mse']:.2e} / {y['relative_mse']:.2e}",
                         f"{r['cost_ratio']:.2f}", f"{num(p['outliers'])} / {num(y['outliers'])}"])
    bright = [[case, ", ".join(f"{x:.3f}" for x in d["cases"][case]["brightness_rgb"]),
               num(d["cases"][case]["object_pixels"])]
              for case in ["bare", "fur"] if case in d["cases"]]
    return (table(["scene", "spp", "render CPU s, pelage / Cycles", "relative MSE, pelage / Cycles",
                   "CPU s × relative MSE, pelage / Cycles", "outlier pixels, pelage / Cycles"],
                  rows, "lrrrrr") + "\n" +
            table(["scene", "brightness R, G, B: pelage / Cycles (references)", "pixels"],
                  bright, "llr") +
            f"\n`docs/tools/cycles_fur.py`: `{d['scene']}` with a constant skin "
            f"({', '.join(f'{x:g}' for x in d['skin_colour'])}) and the hair's absorption as "
            f"sigma_a, in pelage and in {d['blender']}'s Cycles (CPU, {d['threads']} threads), "
            f"{d['width']}×{d['height']}, each against its own {d['reference_spp']}-spp "
            f"reference over the pixels both cover fully, means over {d['seeds']} seeds. "
            f"Render CPU s: a run's process CPU minus that of a 1-spp run. Outliers: pixels "
            f"off by more than 5 times the reference's mean.\n")


# --- validation.md --------------------------------------------------------------------

def t_presets():
    d = data("presets")["presets"]
    rows, worst1 = [], 0.0
    for name in sorted(d):
        p = d[name]
        seeds = p["seeds"]
        for t, want in p["published"].items():
            got = {s: v["cells_by_type"].get(t, 0) for s, v in seeds.items()}
            errs = [(g - want) / want for g in got.values()]
            g1 = got.get("1")
            if g1 is not None:
                worst1 = max(worst1, abs(g1 - want) / want)
            mean = statistics.mean(got.values())
            rows.append([f"`{name}`", t, num(want),
                         "—" if g1 is None else f"{num(g1)} ({signed_pct((g1 - want) / want)})",
                         f"{num(round(mean))} ({signed_pct((mean - want) / want)})",
                         f"{signed_pct(min(errs))} … {signed_pct(max(errs))}"])
    n = len(next(iter(d.values()))["seeds"])
    return (table(["preset", "type", "published", "ours, seed 1", f"mean of {n} seeds",
                   f"range over {n} seeds"], rows, "llrrrr") +
            f"\nWorst deviation at seed 1: **{pct(worst1)}**.\n")


def t_crps_errors():
    keys = ["roundtrip_max_error", "barycentric_max_error", "edge_map_max_error",
            "vertex_map_max_error", "edge_length_max_error", "inverse_max_error"]
    meshes = [data("crps_cow"), data("crps_sphere")]
    header = ["error (relative to the bounding-box diagonal)"] + [
        f"{mesh_name(m['mesh'])} ({num(m['triangles'])} triangles)" for m in meshes]
    rows = [[f"`{k}`"] + [f"{m[k]:.1e}" for m in meshes] for k in keys]
    rows.append(["non-manifold edges / vertices"] +
                [f"{m['nonmanifold_edges']} / {m['nonmanifold_vertices']}" for m in meshes])
    rows.append(["primary / secondary neighbour maps"] +
                [f"{num(m['primary_maps'])} / {num(m['secondary_maps'])}" for m in meshes])
    return table(header, rows)


def t_lookup_quality():
    rows = []
    for r in lookup_runs():
        for label, x in (("geodesic (default)", r), ("unfolding, edge maps", r["unfolding_edges"]),
                         ("unfolding, edge + vertex maps (Teo)", r["teo_unfolding"])):
            rows.append([mesh_name(r["mesh"]), label, pct(x["geodesic_same_cell"], 2),
                         pct(x["geodesic_same_colour"], 2), pct(x["geodesic_impossible"], 2),
                         pct(x["geodesic_distance_error_max"], 2), pct(x["edge_disagreement"]),
                         pct(x["exhaustive_agreement"])])
    return table(["mesh", "neighbourhood", "same cell as exact geodesics",
                  "same colour", "impossible answers", "largest distance error",
                  "edge disagreement (cracks)", "pruned = exhaustive"], rows)


def t_hair_furnace():
    d = data("bench_hair")
    g = d["furnace_grid"]
    return table(["check", "worst error"], [
        [f"white furnace: ∫ f·\\|cos θ_i\\| dω = 1 for σ_a = 0 ({d['furnace_configs']} random fibres, "
         f"{g[0]} × {g[1]} quadrature)", f"{d['furnace_max_error']:.1e}"],
        ["∫ pdf dω = 1 (same fibres and quadrature)", f"{d['pdf_integral_max_error']:.1e}"],
    ], "lr")


def t_gallery():
    d = data("gallery")["gallery"]
    rows = []
    for name in sorted(d):
        g = d[name]
        target = g["published"].get("spot_fraction_by_area")
        sides = g["published"].get("sides_per_spot")
        for mesh in ("sphere", "cow"):
            m = g[mesh]
            rows.append([f"`{name}`", mesh, num(m["cells"]),
                         f"{m['spot_fraction']:.2f}", f"{m['spot_fraction_by_area']:.2f}",
                         "—" if target is None else f"{target:.2f}",
                         num(m["spot_count"]), f"{m['spot_neighbours_mean']:.1f}",
                         "—" if sides is None else str(sides),
                         f"{m['spot_complexity']:.2f}",
                         f"{m['background_largest_share']:.2f}",
                         f"{m['background_near_spot']:.2f}"])
    return table(["preset", "mesh", "cells", "F by count", "F by area", "published",
                  "spots", "neighbours", "published sides", "complexity",
                  "largest background", "background touching a spot"], rows,
                 "llrrrrrrrrrr")


def t_looks():
    d = data("looks")["looks"]
    rows = []
    for name in sorted(d):
        p = d[name]
        for mesh, runs in sorted(p["meshes"].items(), reverse=True):
            fr = [r["spot_fraction_by_area"] for r in runs["seeds"].values()]
            mean = lambda k: statistics.mean(r[k] for r in runs["seeds"].values())
            rows.append([f"`{name}`", mesh, f"{p['target']:.2f}",
                         f"{statistics.mean(fr):.3f}", f"{min(fr):.3f} … {max(fr):.3f}",
                         num(round(mean("spot_count"))), f"{mean('spot_neighbours_mean'):.1f}",
                         f"{mean('spot_complexity'):.2f}",
                         f"{mean('background_largest_share'):.3f}",
                         f"{mean('background_near_spot'):.2f}"])
    n = len(next(iter(next(iter(d.values()))["meshes"].values()))["seeds"])
    return table(["preset", "mesh", "target", f"F by area, mean of {n} seeds", "range",
                  "spots", "neighbours", "complexity", "largest background",
                  "background touching a spot"], rows, "llrrrrrrrr")


def t_control_measures():
    d = data("control_growth")
    z, m = d["zebra"], d["holstein_cow"]["mask_adherence"][0]
    g = d["cow_growing"]["during_growth"]["growth"]
    dens = [x["density"] / g[0]["density"] for x in g]
    return table(["measure", "value", "target"], [
        ["`zebra`: angle between the stripes and the field, median (quartiles)",
         f"{z['stripe_alignment_median']:.1f}° ({z['stripe_alignment_q1']:.1f}°, "
         f"{z['stripe_alignment_q3']:.1f}°)", "< 15°"],
        [f"`holstein-cow`: share of the area its mask excludes (`{m['only_in']}` = 0) "
         f"that shows {m['type']}", f"{100 * m['violation']:.2f} %", "< 1 %"],
        [f"`cow-growing`: cells per unit area over {len(g) - 1} reshapes, area "
         f"×{g[-1]['area'] / g[0]['area']:.1f}, relative to the start",
         f"{min(dens):.3f} … {max(dens):.3f}", "within 10 %"],
    ], "llr")


def t_growth_pipelines():
    d = data("control_growth")["cow_growing"]
    names = {"founders": "the founders, carried to the adult",
             "during_growth": "pattern during growth (`cow-growing`)",
             "before_growth": "pattern on the newborn, then grown (`before_growth`)"}
    rows = []
    for run in ["founders", "during_growth", "before_growth"]:
        r = d[run]
        q = r["spot_area_quantiles"]
        rows.append([names[run], f"{num(r['cells_by_type']['F'])} / {num(r['cells_by_type']['B'])}",
                     num(r["spot_count"]), f"{q['median']:.5f}", f"{q['q90']:.4f}", f"{q['max']:.3f}"])
    return table(["adult (areas in the rest mesh's units)", "F / B cells", "spots",
                  "median spot", "q90", "largest"], rows, "lrrrrr")


def t_clip_fox():
    d = data("clip_fox")
    rows = []
    for r in d["runs"]:
        f = r["frames"]
        mean = lambda k: sum(x[k] for x in f) / len(f)
        rows.append(["sharp" if r["shutter"] == 0 else f"[0, {r['shutter']:g}]",
                     str(len(f)), f"{mean('setup_seconds'):.2f}",
                     f"{1000 * mean('pose_seconds'):.1f}", f"{mean('fur_grow_seconds'):.2f}",
                     f"{mean('fur_embree_seconds'):.2f}", f"{mean('seconds'):.2f}",
                     num(max(x["peak_rss_mb"] for x in f)), num(f[0]["fur_strands"])])
    r0 = d["runs"][0]
    return (table(["shutter", "frames", "set-up s", "posing ms", "fur growth s",
                   "fur BVH s", "render s", "peak MB", "strands"], rows, "lrrrrrrrr") +
            f"\nMeans per frame: `pelage look {d['mesh']} --clip \"{d['clip']}\" --fur "
            f"--frames 200-207 --res {r0['width']}x{r0['height']} --spp {r0['spp']} "
            f"--shutter S --stats-json …` (all cores).\n")


def t_look_animals():
    d = data("look_animals")
    rows = []
    for r in d["runs"]:
        dense = r["source"].startswith("cow.off")
        wall_target, mb_target = (60, 3000) if dense else (30, 1500)
        if "timeout_seconds" in r:
            rows.append([r["mesh"], r["source"], "—", "—", "—",
                         f"> {r['timeout_seconds']}", "—", "no"])
            continue
        if r["exit_code"] != 0:
            rows.append([r["mesh"], r["source"], "—", "—", "—", num(r["wall_seconds"]),
                         num(r["peak_rss_mb"]), "exit " + str(r["exit_code"])])
            continue
        met = r["wall_seconds"] <= wall_target and r["peak_rss_mb"] <= mb_target
        rows.append([r["mesh"], r["source"], num(r["rendered_triangles"]),
                     num(r.get("cells")), num(r.get("growth_seconds")),
                     num(r["wall_seconds"]), num(r["peak_rss_mb"]),
                     f"yes (≤ {wall_target} s, ≤ {mb_target / 1000:g} GB)" if met
                     else f"no (≤ {wall_target} s, ≤ {mb_target / 1000:g} GB)"])
    return (table(["mesh", "from", "triangles rendered", "cells", "pattern s", "wall s",
                   "peak MB", "within target"], rows, "llrrrrrl") +
            f"\n`pelage look MESH --res {d['res']} --spp {d['spp']}` with the default preset "
            "(giraffe-reticulata), each a separate process on all cores, from reading the "
            "mesh to the written EXR; *pattern s* is from the mesh to the `.cells` file, "
            "remeshing included (`docs/tools/look_animals.py`).\n")


def t_explore():
    d = data("explore")
    rows = []
    for c in d["changes"]:
        rows.append([num(c["w_r"]), num(c["change_to_pattern_s"]), num(c["server_first_s"]),
                     num(c["preview_s"]), num(c["full_s"]), num(c["spots"]),
                     num(c["spot_fraction_by_area"])])
    met = d["change_to_pattern_median_s"] <= 1
    return (table(["w_r dragged to", "change → first pattern shown, s", "server's share, s",
                   "preview done, s", "full scale done, s", "spots", "spot fraction by area"],
                  rows) +
            f"\nMedian from a changed control to the first pattern on the page: "
            f"**{num(d['change_to_pattern_median_s'])} s** "
            f"({'within' if met else 'over'} the 1 s target). While the server simulated, "
            f"the page turned its view at {num(d['fps_while_simulating'])} frames per second "
            f"(longest gap {num(d['longest_frame_gap_s'])} s), drawn in software. The "
            f"path-traced preview (480×270, 64 spp) took {num(d['render_480x270_64spp_s'])} s; "
            f"`pelage render` of the saved scene "
            f"{'gave the very same image' if d['saved_scene_renders_the_same_image'] else 'gave another image'}"
            f". `pelage explore` on {d['mesh']} with {d['preset']} (seed {d['seed']}, "
            f"{num(d['cells'])} cells at full scale), driven in {d['browser']} on the same two "
            f"cores (`docs/tools/explore_page.py`).\n")


TABLES = {
    "machine": t_machine, "crps": t_crps, "sim": t_sim, "sim-density": t_sim_density, "sim-mclone": t_sim_mclone, "sim-neighbours": t_sim_neighbours, "default-job": t_default_job,
    "lookup": t_lookup, "lookup-lanes": t_lookup_lanes,
    "lookup-density": t_lookup_density, "render": t_render,
    "compare": t_compare, "hair": t_hair, "fur": t_fur, "export": t_export, "fur-colour": t_fur_colour,
    "fur-comb": t_fur_comb, "fur-glitter": t_fur_glitter,
    "fur-regularisation": t_fur_regularisation,
    "fur-slab": t_fur_slab, "noise": t_noise, "denoise": t_denoise, "cycles-fur": t_cycles_fur, "presets": t_presets,
    "crps-errors": t_crps_errors, "lookup-quality": t_lookup_quality,
    "hair-furnace": t_hair_furnace, "gallery": t_gallery, "looks": t_looks,
    "control-measures": t_control_measures, "growth-pipelines": t_growth_pipelines,
    "clip-fox": t_clip_fox, "look-animals": t_look_animals, "explore": t_explore,
}


def t_fields(name):
    """One of the scene file's reference tables, as `pelage fields NAME` prints it."""
    import subprocess
    return subprocess.run([PELAGE, "fields", name], check=True, capture_output=True,
                          text=True).stdout


for _name in ("camera", "film", "lights", "objects", "transform", "material", "integrator",
              "animation", "fur"):
    TABLES["fields-" + _name] = lambda n=_name: t_fields(n)


def regenerate(text, path):
    def sub(m):
        name = m.group("name")
        if name not in TABLES:
            sys.exit(f"make_tables: {path}: unknown generated region '{name}'")
        return m.group(1) + TABLES[name]() + m.group(4)
    return MARKER.sub(sub, text)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--check", action="store_true",
                    help="exit 1 if a file is out of date, writing nothing")
    args = ap.parse_args()
    stale = []
    for name in FILES:
        path = os.path.join(DOCS, name)
        with open(path, encoding="utf-8") as f:
            old = f.read()
        new = regenerate(old, path)
        if new != old:
            stale.append(path)
            if not args.check:
                with open(path, "w", encoding="utf-8") as f:
                    f.write(new)
    if args.check:
        for path in stale:
            print(f"make_tables: {os.path.relpath(path)} is out of date "
                  f"(run python3 docs/tools/make_tables.py)", file=sys.stderr)
        return 1 if stale else 0
    for path in stale:
        print(f"make_tables: rewrote {os.path.relpath(path)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
