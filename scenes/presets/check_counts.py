#!/usr/bin/env python3
"""Runs every preset that has published counts and prints a Markdown table of final
counts by type against the published ones (the ±10 % check).
Usage: scenes/presets/check_counts.py build/bin/pelage [mesh] [seed]"""
import json, os, subprocess, sys, tempfile

pelage = sys.argv[1]
mesh = sys.argv[2] if len(sys.argv) > 2 else "procedural:sphere:20x20"
seed = sys.argv[3] if len(sys.argv) > 3 else "1"
here = os.path.dirname(os.path.abspath(__file__))
rows, worst = [], 0.0
for f in sorted(os.listdir(here)):
    if not f.endswith(".json"):
        continue
    preset = json.load(open(os.path.join(here, f)))
    published = preset.get("published", {}).get("cells_by_type")
    if not published:
        continue
    with tempfile.TemporaryDirectory() as tmp:
        stats = os.path.join(tmp, "s.json")
        subprocess.run([pelage, "sim", "--mesh", mesh, "--preset", os.path.join(here, f),
                        "--seed", seed, "--stats-json", stats], check=True, stdout=subprocess.DEVNULL)
        s = json.load(open(stats))
    cells = []
    for name, want in published.items():
        got = s["cells_by_type"].get(name, 0)
        err = (got - want) / want
        worst = max(worst, abs(err))
        cells.append(f"{name} {got} / {want} ({100 * err:+.1f} %)")
    rows.append(f"| {preset['name']} | {'; '.join(cells)} | {s['relax_steps']} | {s['seconds']:.2f} |")
print(f"mesh {mesh}, seed {seed}\n")
print("| preset | final cells: ours / published | relax steps | seconds |")
print("|---|---|---|---|")
print("\n".join(rows))
print(f"\nworst deviation {100 * worst:.1f} %")
sys.exit(0 if worst <= 0.10 else 1)
