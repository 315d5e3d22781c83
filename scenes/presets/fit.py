#!/usr/bin/env python3
"""Fits a preset to target statistics of its look by a grid search.

Every combination of the grid's values is grown with `pelage sim` over the given seeds
and measured with `pelage stats --mesh --json`; combinations are ranked by the summed
squared distance to the targets, each divided by its tolerance. Prints a Markdown table,
best first, and with --write the best preset.

  scenes/presets/fit.py build/bin/pelage scenes/presets/giraffe-reticulata.json \\
      --grid 'adhesion[0][0]=0.2,0.5' --grid 'types[0].initial_probability=0.01,0.016' \\
      --target spot_fraction_by_area=0.8:0.02 --target background_components=1:0.5 \\
      --mesh procedural:sphere:20x20 --seeds 1,2 --write fitted.json

A grid key is a path into the preset (types[i].field, adhesion[i][j], simulation.field);
setting types[i].initial_probability also sets the other types' probabilities in
proportion, so they still sum to 1; setting adhesion[i][j] also sets [j][i]. Targets are
keys of `pelage stats --json` plus spots_per_founder (spot_count over the initial F
cells)."""
import argparse, itertools, json, os, re, subprocess, sys, tempfile


def set_path(preset, path, value):
    m = re.fullmatch(r"types\[(\d+)\]\.(\w+)", path)
    if m:
        i, field = int(m.group(1)), m.group(2)
        preset["types"][i][field] = value
        if field == "initial_probability":
            rest = [t for k, t in enumerate(preset["types"]) if k != i]
            total = sum(t["initial_probability"] for t in rest)
            for t in rest:
                t["initial_probability"] = (
                    (1 - value) * t["initial_probability"] / total if total > 0
                    else (1 - value) / len(rest))
        return
    m = re.fullmatch(r"adhesion\[(\d+)\]\[(\d+)\]", path)
    if m:
        i, j = int(m.group(1)), int(m.group(2))
        preset["adhesion"][i][j] = preset["adhesion"][j][i] = value
        return
    m = re.fullmatch(r"simulation\.(\w+)", path)
    if m:
        sim = preset["simulation"]
        if m.group(1) in ("initial_cells", "initial_density", "initial_spacing"):
            for k in ("initial_cells", "initial_density", "initial_spacing"):
                sim.pop(k, None)
        sim[m.group(1)] = value
        return
    sys.exit(f"fit.py: cannot set '{path}' (types[i].field, adhesion[i][j], simulation.field)")


def measure(pelage, preset, mesh, seed, tmp):
    path = os.path.join(tmp, "preset.json")
    cells = os.path.join(tmp, "fit.cells")
    sim_json = os.path.join(tmp, "sim.json")
    json.dump(preset, open(path, "w"))
    subprocess.run([pelage, "sim", "--mesh", mesh, "--preset", path, "--seed", str(seed),
                    "-o", cells, "--stats-json", sim_json], check=True,
                   stdout=subprocess.DEVNULL)
    out = subprocess.run([pelage, "stats", cells, "--mesh", mesh, "--json",
                          "--area-samples", "100000"],
                         check=True, capture_output=True, text=True).stdout
    stats = json.loads(out)
    sim = json.load(open(sim_json))
    f = next((t for t in preset["types"] if t["name"] == "F"), preset["types"][0])
    founders = max(1.0, sim["initial_cells"] * f["initial_probability"])
    stats["spots_per_founder"] = stats["spot_count"] / founders
    stats["seconds"] = sim["seconds"]
    return stats


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("pelage")
    ap.add_argument("preset")
    ap.add_argument("--grid", action="append", default=[], help="PATH=V1,V2,...")
    ap.add_argument("--target", action="append", default=[], help="KEY=VALUE:TOLERANCE")
    ap.add_argument("--mesh", default="procedural:sphere:20x20")
    ap.add_argument("--seeds", default="1,2")
    ap.add_argument("--show", default="", help="extra stats keys to print, comma-separated")
    ap.add_argument("--founder-spacing", type=float,
                    help="hold the F founders' spacing (a fraction of the body length): "
                         "initial_spacing = this x sqrt(P(F))")
    ap.add_argument("--write", help="write the best preset here")
    a = ap.parse_args()

    base = json.load(open(a.preset))
    grid = []
    for g in a.grid:
        path, values = g.split("=", 1)
        grid.append((path, [json.loads(v) for v in values.split(",")]))
    targets = []
    for t in a.target:
        key, rest = t.split("=", 1)
        value, tolerance = rest.split(":")
        targets.append((key, float(value), float(tolerance)))
    seeds = [int(s) for s in a.seeds.split(",")]
    show = [k for k in a.show.split(",") if k]

    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for values in itertools.product(*[v for _, v in grid]):
            preset = json.loads(json.dumps(base))
            for (path, _), v in zip(grid, values):
                set_path(preset, path, v)
            if a.founder_spacing:
                f = next((t for t in preset["types"] if t["name"] == "F"), preset["types"][0])
                set_path(preset, "simulation.initial_spacing",
                         round(a.founder_spacing * f["initial_probability"] ** 0.5, 6))
            runs = [measure(a.pelage, preset, a.mesh, s, tmp) for s in seeds]
            mean = {k: sum(r[k] for r in runs) / len(runs)
                    for k in runs[0] if isinstance(runs[0][k], (int, float))}
            loss = sum(((r[k] - v) / tol) ** 2 for r in runs for k, v, tol in targets)
            rows.append((loss / len(runs), values, mean, preset))
            print(f"  {dict(zip([p for p, _ in grid], values))}: loss {loss / len(runs):.3g}",
                  file=sys.stderr)
    rows.sort(key=lambda r: r[0])
    keys = [k for k, _, _ in targets] + show + ["seconds"]
    print(f"mesh {a.mesh}, seeds {a.seeds}; targets: " +
          ", ".join(f"{k} {v} ± {t}" for k, v, t in targets) + "\n")
    print("| loss | " + " | ".join(p for p, _ in grid) + " | " + " | ".join(keys) + " |")
    print("|---" * (1 + len(grid) + len(keys)) + "|")
    for loss, values, mean, _ in rows:
        print(f"| {loss:.3g} | " + " | ".join(str(v) for v in values) + " | " +
              " | ".join(f"{mean.get(k, float('nan')):.3g}" for k in keys) + " |")
    if a.write and rows:
        json.dump(rows[0][3], open(a.write, "w"), indent=2)
        print(f"\nwrote {a.write}")


if __name__ == "__main__":
    main()
