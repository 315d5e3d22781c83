#!/usr/bin/env bash
# Re-runs every benchmark and validation command whose output docs/performance.md and
# docs/validation.md show, writing the JSON files of docs/data/. Then run
#   python3 docs/tools/make_tables.py
# to rewrite the generated tables. Sizes are kept small (a few CPU-minutes in all); every
# command runs under `nice -n 19`, one at a time, on one thread where the command allows.
#
# Usage: docs/tools/run_benchmarks.sh [PELAGE_BINARY]     (default: build/bin/pelage)
# Needs the sample meshes (scenes/fetch_meshes.sh) and python3.
set -euo pipefail
repo="$(cd "$(dirname "$0")/../.." && pwd)"
pelage="$(realpath "${1:-$repo/build/bin/pelage}")"
cd "$repo"
export PELAGE_DATA_DIR="${PELAGE_DATA_DIR:-$repo}"
out=docs/data
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out" build
if [ ! -f scenes/meshes/cow.off ]; then
    echo "run_benchmarks.sh: run scenes/fetch_meshes.sh first" >&2
    exit 2
fi

log="$work/times.tsv"
run() {   # run NAME COMMAND...: time one command (wall seconds go to run_times.json)
    local name="$1"; shift
    echo "run_benchmarks: $name" >&2
    local t0 t1
    t0=$(date +%s.%N)
    nice -n 19 "$@"
    t1=$(date +%s.%N)
    printf '%s\t%s\n' "$name" "$(echo "$t1 - $t0" | bc)" >>"$log"
}

# --- The machine the figures come from ---
python3 - "$pelage" >"$out/machine.json" <<'PY'
import json, os, platform, subprocess, sys
model = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo")
              if l.startswith("model name")), platform.processor())
version = subprocess.run([sys.argv[1], "--version"], capture_output=True, text=True).stdout.strip()
print(json.dumps({"cpu": model, "logical_cpus": os.cpu_count(),
                  "system": platform.system() + " " + platform.machine(),
                  "pelage": version}, indent=2))
PY

# --- Performance ---
run bench_crps    "$pelage" bench crps --repeat 2 --threads 1 -q \
                      --stats-json "$out/bench_crps.json"
run bench_sim     "$pelage" bench sim --initial-cells 1000 5000 10000 --large-initial 25000 \
                      --large-target 100000 --threads 1 -q --stats-json "$out/bench_sim.json"
run bench_lookup  "$pelage" bench lookup --cell-count 20000 --queries 500000 --threads 1 -q \
                      --stats-json "$out/bench_lookup.json"
run bench_render  "$pelage" bench render --res 1280x720 --spp 4 --repeat 3 -q \
                      --stats-json "$out/bench_render.json"
run bench_hair    "$pelage" bench hair --configs 16 -q --stats-json "$out/bench_hair.json"
run bench_fur     "$pelage" bench fur --strands 20000 100000 2500000 10000000 --res 320x240 \
                      --spp 4 --threads 1 \
                      -q --stats-json "$out/bench_fur.json"
run bench_export  "$pelage" bench export scenes/fur_cow_giraffe.json --density-scale 3 \
                      --threads 2 -q --stats-json "$out/bench_export.json"
run fur_colour    "$pelage" bench fur-colour --res 320x180 --spp 32 --slab-spp 128 -q \
                      --stats-json "$out/fur_colour.json"
# Each animal preset's colours as `look` shows them (docs/guide/presets.md).
run preset_colour "$pelage" bench preset-colour -q --stats-json "$out/preset_colour.json"
run fur_comb      "$pelage" bench fur-comb -q --stats-json "$out/fur_comb.json" \
                      --fur-keys '{"comb_angle": 20, "comb_jitter": 4, "gravity": 0.2, "clump": 0.2}'
# Noise against a converged reference, cached in build/noise_refs (keyed by the binary
# and the inputs): the first run after a build renders the references (a few minutes).
run sim_walter_cheetah "$pelage" sim --mesh scenes/meshes/cow.off --preset walter-cheetah \
                      --seed 1 --threads 1 -o scenes/cow_walter_cheetah.cells
run bench_noise   "$pelage" bench noise scenes/bench_cow_sun_sky.json --spp 16 64 256 \
                      --seeds 2 --cache build/noise_refs -q --stats-json "$out/bench_noise.json"
run bench_noise_fur "$pelage" bench noise scenes/bench_cow_sun_sky_fur.json --spp 16 64 \
                      --seeds 2 --reference-spp 1024 --cache build/noise_refs \
                      -q --stats-json "$out/bench_noise_fur.json"
# The same coat from four times as far (strands 0.05 px wide): the fibres against their
# reference, then widened to a pixel (min_pixel_width 1) against the same reference.
run bench_noise_fur_far "$pelage" bench noise scenes/bench_cow_far_fur.json --res "" \
                      --spp 16 64 --seeds 2 --reference-spp 1024 --cache build/noise_refs \
                      -q --stats-json "$out/bench_noise_fur_far.json"
far_ref=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["reference"]["file"])' \
              "$out/bench_noise_fur_far.json")
run bench_noise_fur_far_widened "$pelage" bench noise scenes/bench_cow_far_fur_widened.json \
                      --res "" --spp 16 64 --seeds 2 --reference "$far_ref" \
                      -q --stats-json "$out/bench_noise_fur_far_widened.json"
# The denoiser on the same scenes and references: its gain, its bias and halo at the
# pattern's edges, and its cost on a 1920×1080 frame against that frame's 64-spp render.
run bench_denoise "$pelage" bench noise scenes/bench_cow_sun_sky.json --spp 16 64 256 \
                      --denoise --seeds 4 --cache build/noise_refs -q --stats-json "$out/bench_denoise.json"
run bench_denoise_fur "$pelage" bench noise scenes/bench_cow_sun_sky_fur.json --spp 16 64 \
                      --denoise --seeds 2 --reference-spp 1024 --cache build/noise_refs \
                      -q --stats-json "$out/bench_denoise_fur.json"
run denoise_1080  "$pelage" render scenes/bench_cow_sun_sky.json --res 1920x1080 --spp 64 \
                      --denoise -q -o "$work/denoise_1080.exr" \
                      --stats-json "$out/denoise_1080.json"
run sim_cheetah   "$pelage" sim --mesh procedural:sphere:20x20 --preset teo-cheetah --seed 1 \
                      --threads 1 -o scenes/sphere_cheetah.cells
run compare       "$pelage" compare scenes/sphere_cheetah.json --res 500x500 --spp 2 \
                      --shaders clonal_mosaic,worley,perlin,texture,diffuse --repeat 3 \
                      --atlas-res 1024 --lookups 100000 --threads 1 \
                      --stats-json "$out/compare_sphere_cheetah.json"

# --- Validation and the default job's statistics ---
run crps_cow      "$pelage" crps --mesh scenes/meshes/cow.off --threads 1 \
                      --stats-json "$out/crps_cow.json"
run crps_sphere   "$pelage" crps --mesh procedural:sphere:20x20 --threads 1 \
                      --stats-json "$out/crps_sphere.json"
run sim_cow       "$pelage" sim --mesh scenes/meshes/cow.off --preset giraffe-reticulata \
                      --seed 1 --threads 1 -o "$work/cow_giraffe.cells" \
                      --stats-json "$out/sim_cow_giraffe.json"
run sim_cow_2threads "$pelage" sim --mesh scenes/meshes/cow.off --preset giraffe-reticulata \
                      --seed 1 --threads 2 -o "$work/cow_giraffe_2threads.cells" \
                      --stats-json "$out/sim_cow_giraffe_2threads.json"
run stats_cow     "$pelage" stats "$work/cow_giraffe.cells" --mesh scenes/meshes/cow.off \
                      --stats-json "$out/stats_cow_giraffe.json"

# Every preset with published counts, seeds 1-5, on Teo's 760-triangle sphere.
for preset in scenes/presets/*.json; do
    name=$(basename "$preset" .json)
    python3 -c 'import json,sys; sys.exit(0 if json.load(open(sys.argv[1])).get("published", {}).get("cells_by_type") else 1)' \
        "$preset" || continue
    for seed in 1 2 3 4 5; do
        run "preset_${name}_$seed" "$pelage" sim --mesh procedural:sphere:20x20 \
            --preset "$preset" --seed "$seed" --threads 1 \
            --stats-json "$work/preset_${name}_$seed.json" >/dev/null
    done
done
python3 - "$work" >"$out/presets.json" <<'PY'
import glob, json, os, sys
work, runs = sys.argv[1], {}
for f in sorted(glob.glob("scenes/presets/*.json")):
    preset = json.load(open(f))
    published = preset.get("published", {}).get("cells_by_type")
    if not published:
        continue
    seeds = {}
    for s in sorted(glob.glob(os.path.join(work, "preset_%s_*.json" % preset["name"]))):
        st = json.load(open(s))
        seeds[str(st["seed"])] = {"cells_by_type": st["cells_by_type"],
                                  "relax_steps": st["relax_steps"]}
    runs[preset["name"]] = {"published": published, "mesh": "procedural:sphere:20x20",
                            "seeds": seeds}
print(json.dumps({"presets": runs}, indent=2, sort_keys=True))
PY

# A walking fox, frame by frame: posing, fur and render per frame, sharp and with a
# half-frame shutter. The Khronos sample fox is not shipped; PELAGE_FOX names the file
# (as for images/make_images.sh), and without it clip_fox.json is left as it is.
if [ -n "${PELAGE_FOX:-}" ] && [ -f "$PELAGE_FOX" ]; then
    for shutter in 0 0.5; do
        run "clip_fox_$shutter" "$pelage" look "$PELAGE_FOX" \
            --clip "Armature|Take 001|BaseLayer" --frames 200-207 --res 480x270 --spp 16 \
            --fur --shutter "$shutter" -o "$work/fox_$shutter.exr" -q \
            --stats-json "$work/clip_fox_$shutter.json" 2>/dev/null
    done
    python3 - "$work" >"$out/clip_fox.json" <<'PY'
import json, os, sys
runs = []
for shutter in ("0", "0.5"):
    st = json.load(open(os.path.join(sys.argv[1], "clip_fox_%s.json" % shutter)))
    runs.append({"shutter": float(shutter), "width": st["width"], "height": st["height"],
                 "spp": st["spp"], "threads": st["threads"], "frames": st["frames"]})
print(json.dumps({"mesh": "Fox.glb", "clip": "Armature|Take 001|BaseLayer", "runs": runs},
                 indent=2, sort_keys=True))
PY
fi

# From a mesh to a picture: `pelage look` on every sample animal and a 1.5 M-triangle
# cow (all cores; the fox too when PELAGE_FOX names it).
run look_animals python3 docs/tools/look_animals.py "$pelage" "$work" \
    >"$out/look_animals.json"

# `pelage explore` on the cow in headless Chromium: its interactivity, and the docs'
# screenshots of the page (images/explore_cow*.png).
run explore python3 docs/tools/explore_page.py "$pelage" scenes/meshes/cow.off images \
    >"$out/explore.json"

python3 - "$log" >"$out/run_times.json" <<'PY'
import json, sys
rows = [l.rstrip("\n").split("\t") for l in open(sys.argv[1])]
print(json.dumps({"wall_seconds": {k: round(float(v), 2) for k, v in rows},
                  "total_wall_seconds": round(sum(float(v) for _, v in rows), 1)}, indent=2))
PY
# Paths inside the repository are recorded relative to it; temporary paths by name only.
python3 - "$repo" "$work" <<'PY'
import glob, json, os, sys
repo, work = sys.argv[1] + "/", sys.argv[2] + "/"
def clean(v):
    if isinstance(v, dict): return {k: clean(x) for k, x in v.items()}
    if isinstance(v, list): return [clean(x) for x in v]
    if isinstance(v, str) and v.startswith(repo): return v[len(repo):]
    if isinstance(v, str) and v.startswith(("/tmp/", work)): return os.path.basename(v)
    return v
for f in glob.glob("docs/data/*.json"):
    d = clean(json.load(open(f)))
    with open(f, "w") as out:
        out.write(json.dumps(d, indent=2) + "\n")
PY
echo "run_benchmarks: done; now run python3 docs/tools/make_tables.py" >&2
