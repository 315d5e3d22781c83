#!/usr/bin/env python3
"""pelage against Blender Cycles on the same furry and bare cow, every setting matched:
how bright each renders the fur, and what a clean image costs in each.

The scene is scenes/bench_cow_sun_sky_fur.json (its camera, sun, sky, film, bounces and
strands) with a constant skin colour instead of the pattern and the hair's absorption
given as sigma_a, so nothing depends on either renderer's pigment or shader mappings.
Both renderers get random roots (area-uniform, neither jittered nor stratified),
straight strands along the interpolated normal, the same root and tip radii, β_m, β_n,
α and η, and no clamping, Filter Glossy, light threshold, adaptive sampling or
denoising (docs/tools/cycles_scene.py builds Cycles' side). Russian roulette, an
efficiency setting, is each renderer's default.

Each renderer is measured against its own converged reference over the pixels both
references cover fully (alpha >= 0.999):
  * brightness: the references' mean per channel, pelage / Cycles;
  * cost: render CPU seconds (a run's process CPU minus that of a 1-spp run, so loading
    and BVH builds do not count) × relative MSE (MSE / the reference's mean squared),
    pelage / Cycles: below 1 pelage reaches a given noise level sooner;
  * outliers: pixels off by more than 5 times the reference's mean in some channel.
Writes one JSON object (docs/data/cycles_fur.json; docs/tools/make_tables.py turns it
into the table of docs/performance.md).

Blender is a measuring tool only; nothing in the build or the tests needs it.
Needs: Debian's blender, python3-numpy, python3-openimageio (run with /usr/bin/python3),
the sample meshes (scenes/fetch_meshes.sh), a built pelage.

Usage: /usr/bin/python3 docs/tools/cycles_fur.py [--pelage build/bin/pelage]
           [--res 640x360] [--spp 16 64] [--seeds 2] [--reference-spp 1024]
           [--out docs/data/cycles_fur.json]
"""
import argparse
import copy
import json
import os
import resource
import subprocess
import sys
import tempfile

import numpy as np
import OpenImageIO as oiio

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENE = os.path.abspath(os.environ.get("CYCLES_FUR_SCENE") or
                        os.path.join(REPO, "scenes", "bench_cow_sun_sky_fur.json"))
SKIN = [0.5, 0.35, 0.2]          # the constant skin colour (linear)
REFERENCE_SEED = 999983          # no measured run uses it


def run_cpu(cmd, log):
    """Runs cmd; returns the CPU seconds (user + system) it and its children used."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    with open(log, "a", encoding="utf-8") as out:
        r = subprocess.run(cmd, stdout=out, stderr=subprocess.STDOUT)
    if r.returncode != 0:
        sys.exit(f"cycles_fur: {' '.join(cmd)} failed (exit {r.returncode}); see {log}")
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def read_rgba(path):
    img = oiio.ImageInput.open(path)
    if img is None:
        sys.exit(f"cycles_fur: cannot read {path}")
    s = img.spec()
    a = np.array(img.read_image(0, 0, 0, 4, "float")).reshape(s.height, s.width, 4)
    img.close()
    return a


def matched(bench, with_fur, width, height, skin=SKIN):
    """The pelage scene and the Cycles configuration of one case."""
    scene = copy.deepcopy(bench)
    obj = scene["objects"][0]
    mesh = os.path.join(os.path.dirname(SCENE), obj["mesh"])
    obj["mesh"] = mesh
    obj.pop("cells", None)
    obj.pop("pattern", None)
    obj["material"] = {"shader": "diffuse", "params": {"albedo": skin}}
    fur = obj.pop("fur")
    hair = None
    if with_fur:
        eu, pheo = fur.pop("melanin")
        # pbrt's and Cycles' melanin absorption (Chiang et al. 2016, §4.1), per unit radius
        sigma_a = [eu * e + pheo * p for e, p in
                   zip((0.419, 0.697, 1.37), (0.187, 0.4, 1.05))]
        hair = {"density": fur["density"], "length": fur["length"],
                "root_radius": fur["root_radius"], "tip_radius": fur["tip_radius"],
                "segments": fur["segments"], "seed": fur.get("seed", 1),
                "sigma_a": sigma_a, "beta_m": fur.get("beta_m", 0.25),
                "beta_n": fur.get("beta_n", 0.3), "alpha_deg": fur.get("alpha", 2.0),
                "eta": 1.55}
        fur.update({"sigma_a": sigma_a, "beta_m": hair["beta_m"], "beta_n": hair["beta_n"],
                    "alpha": hair["alpha_deg"], "melanin_jitter": 0})
        obj["fur"] = fur
    # Russian roulette is each renderer's own (an efficiency setting, unbiased in both):
    # pelage's from its default depth, Cycles' from its first bounce with probability
    # sqrt(max throughput) and min_light_bounces 0.
    scene["integrator"].pop("rr_depth", None)
    scene["film"].update({"width": width, "height": height})
    scene["film"].pop("preview", None)
    env = next(l for l in scene["lights"] if l["type"] == "environment")
    sun = next(l for l in scene["lights"] if l["type"] == "distant")
    cycles = {"mesh": mesh, "camera": scene["camera"], "width": width, "height": height,
              "filter_radius": scene["film"]["filter"]["radius"],
              "environment": {"colour": env["colour"], "intensity": env["intensity"]},
              "sun": {"direction": sun["direction"], "angle": sun["angle"],
                      "colour": sun["colour"], "intensity": sun["intensity"]},
              "skin_colour": skin, "fur": hair,
              "max_depth": scene["integrator"]["max_depth"]}
    return scene, cycles


class Renderers:
    def __init__(self, args, work):
        self.args, self.work = args, work
        self.log = os.path.join(work, "log.txt")

    def pelage(self, scene, spp, seed, out):
        path = os.path.join(self.work, "pelage.json")
        with open(path, "w", encoding="utf-8") as f:
            json.dump(scene, f, indent=1)
        return run_cpu([self.args.pelage, "render", path, "--spp", str(spp), "--sampler-seed",
                        str(seed), "--threads", str(self.args.threads), "-q", "-o", out],
                       self.log)

    def cycles(self, cfg, spp, seed, out):
        c = dict(cfg, spp=spp, seed=seed % 2**31, threads=self.args.threads,
                 output=out)
        path = os.path.join(self.work, "cycles.json")
        with open(path, "w", encoding="utf-8") as f:
            json.dump(c, f)
        return run_cpu([self.args.blender, "-b", "--factory-startup", "-noaudio",
                        "--python-exit-code", "1", "-P",
                        os.path.join(REPO, "docs", "tools", "cycles_scene.py"), "--",
                        path], self.log)


def measure(case, scene, cfg, r, args):
    w = r.work
    refs = {}
    for name, render, c in [("pelage", r.pelage, scene), ("cycles", r.cycles, cfg)]:
        out = os.path.join(w, f"{case}_{name}_ref.exr")
        print(f"cycles_fur: {case}: {name} reference, {args.reference_spp} spp",
              file=sys.stderr)
        render(c, args.reference_spp, REFERENCE_SEED, out)
        refs[name] = read_rgba(out)
    # Pixels the object covers fully in both: pelage keeps the background's radiance in
    # a partly covered pixel, Cycles' transparent film does not.
    mask = (refs["pelage"][..., 3] >= 0.999) & (refs["cycles"][..., 3] >= 0.999)
    means = {k: refs[k][..., :3][mask].mean(axis=0) for k in refs}
    result = {"object_pixels": int(mask.sum()),
              "reference_mean_rgb": {k: means[k].tolist() for k in means},
              "brightness_rgb": (means["pelage"] / means["cycles"]).tolist(),
              "by_spp": []}
    setup = {}
    for name, render, c in [("pelage", r.pelage, scene), ("cycles", r.cycles, cfg)]:
        setup[name] = render(c, 1, 1, os.path.join(w, f"{case}_{name}_1.exr"))
    for spp in args.spp:
        row = {"spp": spp}
        for name, render, c in [("pelage", r.pelage, scene), ("cycles", r.cycles, cfg)]:
            ref = refs[name][..., :3][mask]
            m = float(ref.mean())
            cpu, mse, outliers = [], [], []
            for seed in range(1, args.seeds + 1):
                print(f"cycles_fur: {case}: {name}, {spp} spp, seed {seed}",
                      file=sys.stderr)
                out = os.path.join(w, f"{case}_{name}_{spp}_{seed}.exr")
                cpu.append(render(c, spp, seed, out) - setup[name])
                err = read_rgba(out)[..., :3][mask] - ref
                mse.append(float((err ** 2).mean()))
                outliers.append(int((np.abs(err).max(axis=1) > 5 * m).sum()))
            row[name] = {"render_cpu_seconds": float(np.mean(cpu)),
                         "setup_cpu_seconds": setup[name], "mse": float(np.mean(mse)),
                         "relative_mse": float(np.mean(mse)) / m ** 2,
                         "outliers": float(np.mean(outliers))}
        p, c = row["pelage"], row["cycles"]
        row["cpu_ratio"] = p["render_cpu_seconds"] / c["render_cpu_seconds"]
        row["relative_mse_ratio"] = p["relative_mse"] / c["relative_mse"]
        row["cost_ratio"] = row["cpu_ratio"] * row["relative_mse_ratio"]
        result["by_spp"].append(row)
    return result


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--pelage", default=os.path.join(REPO, "build", "bin", "pelage"))
    ap.add_argument("--blender", default="blender")
    ap.add_argument("--res", default="640x360")
    ap.add_argument("--spp", type=int, nargs="+", default=[16, 64])
    ap.add_argument("--seeds", type=int, default=2)
    ap.add_argument("--reference-spp", type=int, default=1024)
    ap.add_argument("--threads", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--cases", nargs="+", default=["fur", "bare"], choices=["fur", "bare"])
    ap.add_argument("--out", default=os.path.join(REPO, "docs", "data", "cycles_fur.json"))
    ap.add_argument("--keep", help="keep the images in this directory")
    ap.add_argument("--skin", type=float, nargs=3, default=SKIN,
                    help="the skin's constant colour (linear RGB)")
    args = ap.parse_args()
    width, height = (int(x) for x in args.res.split("x"))
    with open(SCENE, encoding="utf-8") as f:
        bench = json.load(f)
    blender = subprocess.run([args.blender, "--version"], capture_output=True, text=True)
    version = blender.stdout.splitlines()[0] if blender.returncode == 0 else None
    if version is None:
        sys.exit("cycles_fur: blender not found (apt-get install blender)")
    work = args.keep or tempfile.mkdtemp(prefix="pelage-cycles-")
    os.makedirs(work, exist_ok=True)
    r = Renderers(args, work)
    out = {"scene": os.path.relpath(SCENE, REPO), "blender": version,
           "width": width, "height": height, "reference_spp": args.reference_spp,
           "seeds": args.seeds, "threads": args.threads, "skin_colour": args.skin,
           "cases": {}}
    for case in args.cases:
        scene, cfg = matched(bench, case == "fur", width, height, args.skin)
        out["cases"][case] = measure(case, scene, cfg, r, args)
        if case == "fur":
            out["fur"] = cfg["fur"]
    with open(args.out, "w", encoding="utf-8") as f:
        json.dump(out, f, indent=2)
        f.write("\n")
    print(json.dumps({k: v["brightness_rgb"] for k, v in out["cases"].items()}))


if __name__ == "__main__":
    main()
