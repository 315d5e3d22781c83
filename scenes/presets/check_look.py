#!/usr/bin/env python3
"""Grows every preset that states a published spot area by area (published.
spot_fraction_by_area) over seeds 1-5 on the 760-triangle sphere and on the cow, measures
it with `pelage stats --mesh --json`, prints a Markdown table and writes the runs as JSON.
Exits 1 when a run is more than 0.05 from its target.

  scenes/presets/check_look.py build/bin/pelage [--json out.json] [--seeds 1,2,3,4,5]

On the sphere, whose area is 3.4 times a cow's against its length, each run starts from
100 / P(F) cells (about 100 founders) instead of the preset's body scale, which would ask
for some 450 000 cells; the dynamics do not depend on the count (every length scales
with sqrt(A/m))."""
import argparse, json, os, subprocess, sys, tempfile

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(os.path.dirname(here))
KEYS = ["spot_fraction_by_area", "spot_fraction", "spot_count", "spot_area_share_mean",
        "spot_neighbours_mean", "spot_complexity", "background_components",
        "background_largest_share", "background_near_spot"]


def run(pelage, preset, mesh, seed, cells, tmp):
    out = os.path.join(tmp, "look.cells")
    args = [pelage, "sim", "--mesh", mesh, "--preset", preset, "--seed", str(seed), "-o", out]
    if cells:
        args += ["--initial-cells", str(cells)]
    subprocess.run(args, check=True, stdout=subprocess.DEVNULL)
    stats = json.loads(subprocess.run(
        [pelage, "stats", out, "--mesh", mesh, "--json"], check=True, capture_output=True,
        text=True).stdout)
    return {k: stats[k] for k in KEYS} | {"cells": stats["cells"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("pelage")
    ap.add_argument("--json", help="write the runs here")
    ap.add_argument("--seeds", default="1,2,3,4,5")
    a = ap.parse_args()
    seeds = [int(s) for s in a.seeds.split(",")]
    meshes = {"sphere": "procedural:sphere:20x20",
              "cow": os.path.join(root, "scenes", "meshes", "cow.off")}
    if not os.path.exists(meshes["cow"]):
        sys.exit("check_look.py: scenes/meshes/cow.off is missing (scenes/fetch_meshes.sh)")
    runs, worst, rows = {}, 0.0, []
    with tempfile.TemporaryDirectory() as tmp:
        for f in sorted(os.listdir(here)):
            if not f.endswith(".json"):
                continue
            preset = json.load(open(os.path.join(here, f)))
            target = preset.get("published", {}).get("spot_fraction_by_area")
            if target is None:
                continue
            pf = next((t for t in preset["types"] if t["name"] == "F"))["initial_probability"]
            entry = {"target": target, "meshes": {}}
            for name, mesh in meshes.items():
                cells = round(100 / pf) if name == "sphere" else None
                got = {str(s): run(a.pelage, os.path.join(here, f), mesh, s, cells, tmp)
                       for s in seeds}
                entry["meshes"][name] = {"initial_cells": cells, "seeds": got}
                fr = [g["spot_fraction_by_area"] for g in got.values()]
                worst = max([worst] + [abs(x - target) for x in fr])
                mean = lambda k: sum(g[k] for g in got.values()) / len(got)
                rows.append(f"| {preset['name']} | {name} | {target:.2f} | "
                            f"{mean('spot_fraction_by_area'):.3f} ({min(fr):.3f} … {max(fr):.3f}) | "
                            f"{mean('spot_count'):.0f} | {mean('spot_neighbours_mean'):.2f} | "
                            f"{mean('spot_complexity'):.2f} | "
                            f"{mean('background_largest_share'):.3f} | "
                            f"{mean('background_near_spot'):.2f} |")
                print(rows[-1], file=sys.stderr)
            runs[preset["name"]] = entry
    print(f"seeds {a.seeds}\n")
    print("| preset | mesh | target | F by area, mean (range) | spots | neighbours | "
          "complexity | largest background share | background touching a spot |")
    print("|---|---|---|---|---|---|---|---|---|")
    print("\n".join(rows))
    print(f"\nworst distance from the target {worst:.3f}")
    if a.json:
        with open(a.json, "w") as out:
            json.dump({"looks": runs}, out, indent=2, sort_keys=True)
    sys.exit(0 if worst <= 0.05 else 1)


if __name__ == "__main__":
    main()
