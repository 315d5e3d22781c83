#!/usr/bin/env bash
# Regenerates every PNG in images/ that the READMEs show, from this repository's scenes
# and presets, so the pictures always match the code that made them. Needs the build
# and the sample meshes (./quickstart.sh run). A few minutes on two cores.
set -euo pipefail
cd "$(dirname "$0")/.."
pelage=${PELAGE:-build/bin/pelage}
if [ ! -x "$pelage" ] || [ ! -f scenes/meshes/cow.off ]; then
    echo "make_images.sh: run ./quickstart.sh run first (build and sample meshes)" >&2
    exit 2
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The scenes grow their mosaics (their "pattern" blocks) into scenes/*.cells on first use.
# The default job (960×540, 64 spp), shown at 640×360.
$pelage render scenes/cow_giraffe.json -q -o "$tmp/cow_giraffe.exr" \
    --preview "$tmp/cow_giraffe.png"
oiiotool "$tmp/cow_giraffe.png" --resize 640x360 -o images/cow_giraffe.png
$pelage render scenes/triceratops_leopard.json -q -o "$tmp/triceratops.exr" \
    --preview images/triceratops_leopard.png
$pelage render scenes/cow.json --spp 256 -q -o "$tmp/cow.exr" --preview images/cow.png
# CM and the matched baselines, one contact sheet.
$pelage compare scenes/sphere_cheetah.json --sheet images/compare_sphere.png
# Fur and the bare skin under it.
$pelage render scenes/fur_sphere_cheetah.json -q -o "$tmp/fur_sphere.exr" \
    --preview images/fur_sphere_cheetah.png
$pelage render scenes/sphere_cheetah.json --spp 24 -q -o "$tmp/bare_sphere.exr" \
    --preview images/fur_sphere_cheetah_bare.png
$pelage render scenes/fur_cow_giraffe.json -q -o "$tmp/fur_cow.exr" \
    --preview images/fur_cow_giraffe.png
$pelage render scenes/cow_giraffe.json --res 480x270 --spp 16 -q -o "$tmp/bare_cow.exr" \
    --preview images/fur_cow_giraffe_bare.png
# A close-up of the furry giraffe's head, and six frames of its turntable.
$pelage render scenes/fur_cow_head.json -q -o "$tmp/fur_head.exr" \
    --preview images/fur_cow_head.png
$pelage render scenes/fur_cow_turntable.json --frames 0-20 --step 4 -q \
    -o "$tmp/turntable.####.exr"
frames=()
for f in 0000 0004 0008 0012 0016 0020; do
    oiiotool "$tmp/turntable.$f.exr" --ch denoised.R,denoised.G,denoised.B \
        --chnames R,G,B --colorconvert linear sRGB \
        -o "$tmp/turntable.$f.png"
    frames+=("$tmp/turntable.$f.png")
done
oiiotool "${frames[@]}" --mosaic:pad=4 3x2 -o images/fur_cow_turntable.png
# Cryptomatte: the beauty, the matte of the spot type, and the mattes of the clones whose
# founder ids start with 1, pulled out of the EXR by `pelage matte`.
$pelage render scenes/cow_giraffe.json --res 480x270 --spp 32 --cryptomatte -q \
    -o "$tmp/mattes.exr" --preview "$tmp/mattes_beauty.png"
$pelage matte "$tmp/mattes.exr" --layer type --name F -q -o "$tmp/mattes_type.png"
$pelage matte "$tmp/mattes.exr" --layer lineage --name 'cow/clone 1*' -q \
    -o "$tmp/mattes_clones.png"
font=/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf
oiiotool "$tmp/mattes_beauty.png" --text:x=10:y=24:size=18:font=$font "beauty" \
    "$tmp/mattes_type.png" --text:x=10:y=24:size=18:font=$font:color=1,0.3,0.2 \
    "CryptoType: F" \
    "$tmp/mattes_clones.png" --text:x=10:y=24:size=18:font=$font:color=1,0.3,0.2 \
    "CryptoLineage: cow/clone 1*" \
    --mosaic:pad=4 3x1 -o images/cryptomatte_cow.png
# The simulation alone: every cell a dot (pelage preview).
$pelage sim --mesh scenes/meshes/cow.off --preset giraffe-reticulata --initial-cells 3000 --seed 1 \
    -o "$tmp/cow3000.cells"
$pelage preview "$tmp/cow3000.cells" -o images/sim_cow_giraffe_reticulata.png --res 480

font=/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf
# Spatial control and growth (docs/guide/growth-and-control.md): the zebra's stripes
# follow a field, the Holstein's white comes from neural-crest masks, the giraffe's legs
# carry smaller patches; then the growing cow at birth, half grown and adult, its spots
# riding on the skin. Labelled 3×2 sheet.
tiles=()
for preset in zebra holstein-cow giraffe-reticulata-legs; do
    mkdir -p "$tmp/look_$preset"
    $pelage look scenes/meshes/cow.off --preset $preset --seed 1 --res 320x200 --spp 32 -q \
        -o "$tmp/look_$preset/cow.exr"
    oiiotool "$tmp/look_$preset/cow_preview.png" --ch R,G,B \
        --text:x=8:y=192:size=15:font=$font "$preset" -o "$tmp/tile_$preset.png"
    tiles+=("$tmp/tile_$preset.png")
done
for frame in 0 24 47; do
    $pelage render scenes/cow_growing.json --frames $frame --res 320x200 --spp 32 -q \
        -o "$tmp/growing.####.exr" \
        --preview "$tmp/growing_preview.####.png"
    f=$(printf %04d $frame)
    oiiotool "$tmp/growing_preview.$f.png" --ch R,G,B --text:x=8:y=192:size=15:font=$font \
        "cow-growing, month $(( frame * 36 / 47 ))" -o "$tmp/tile_growing_$f.png"
    tiles+=("$tmp/tile_growing_$f.png")
done
oiiotool "${tiles[@]}" --mosaic:pad=4 3x2 -o images/control_and_growth.png

# What the spatial control and growth achieve (docs/data/control_growth.json, tabulated
# in docs/guide/growth-and-control.md): the zebra's stripes against its field, the
# Holstein's mask adherence, and W01's point: the same founders on cow.off give another
# adult when the pattern forms during growth, before it, or not at all.
for preset in zebra holstein-cow; do
    $pelage stats "$tmp/look_$preset/cow.cells" --mesh scenes/meshes/cow.off --json \
        >"$tmp/stats_$preset.json"
done
python3 - scenes/presets/cow-growing.json "$tmp" <<'PY'
import json, sys
preset, tmp = json.load(open(sys.argv[1])), sys.argv[2]
variants = {"before_growth": {"pattern": "before_growth", "end_time": 1000, "target": 5790},
            "founders": {"pattern": "before_growth", "end_time": 1000, "target": 1500}}
for name, v in variants.items():
    p = json.loads(json.dumps(preset))
    p["growth"]["pattern"] = v["pattern"]
    p["simulation"]["end_time"] = v["end_time"]
    p["simulation"]["target_cells"] = v["target"]
    json.dump(p, open(f"{tmp}/cow-growing-{name}.json", "w"))
PY
for run in during_growth before_growth founders; do
    preset=scenes/presets/cow-growing.json
    [ $run != during_growth ] && preset="$tmp/cow-growing-$run.json"
    $pelage sim --mesh scenes/meshes/cow.off --preset "$preset" --surface input --seed 1 -q \
        -o "$tmp/growing_$run.cells" --stats-json "$tmp/growing_$run.json"
    $pelage stats "$tmp/growing_$run.cells" --json >"$tmp/growing_stats_$run.json"
done
python3 - "$tmp" >docs/data/control_growth.json <<'PY'
import json, sys
tmp = sys.argv[1]
def load(name): return json.load(open(f"{tmp}/{name}.json"))
zebra, holstein = load("stats_zebra"), load("stats_holstein-cow")
runs = {}
for run in ["founders", "during_growth", "before_growth"]:
    d, st = load("growing_" + run), load("growing_stats_" + run)
    runs[run] = {k: d[k] for k in ["cells_by_type", "growth", "growth_lost_cells",
                                   "final_cells"] if k in d}
    runs[run].update({k: st[k] for k in ["spot_count", "spot_area_quantiles"]})
print(json.dumps({
    "mesh": "scenes/meshes/cow.off", "seed": 1,
    "zebra": {k: zebra[k] for k in zebra if k.startswith("stripe_")},
    "holstein_cow": {"mask_adherence": holstein["mask_adherence"]},
    "cow_growing": runs}, indent=2, sort_keys=True))
PY

# The gallery (fonts-dejavu-core labels it): every preset on the sphere and on the cow,
# bare and with fur (the coat of scenes/fur_cow_giraffe.json, combed along the preset's
# anisotropy field when it has one, as `pelage look --fur` does), labelled, and the look of each
# measured by `pelage stats --mesh` (docs/data/gallery.json, shown in
# docs/guide/presets.md). Presets scaled to the body (initial_spacing) start from about
# 100 founders on the sphere, whose area against its length is 3.4 times a cow's.
font=/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf
tiles_sphere=() tiles_cow=() tiles_fur=()
echo '{' >"$tmp/gallery.json"
first=1
for preset in scenes/presets/*.json; do
    name=$(basename "$preset" .json)
    # A preset that "extends" another grows its base's cells: its tile would repeat it.
    python3 -c 'import json,sys; sys.exit(1 if "extends" in json.load(open(sys.argv[1])) else 0)' \
        "$preset" || continue
    cells=$(python3 -c 'import json,sys; p=json.load(open(sys.argv[1])); s=p["simulation"]
f=next(t for t in p["types"] if t["name"]=="F") if any(t["name"]=="F" for t in p["types"]) else p["types"][0]
ip=f["initial_probability"]; ip=ip["default"] if isinstance(ip, dict) else ip
print(round(100/ip) if "initial_spacing" in s and ip > 0 else 0)' "$preset")
    for kind in sphere cow; do
        mesh=procedural:sphere:20x20
        [ $kind = cow ] && mesh=scenes/meshes/cow.off
        extra=()
        [ $kind = sphere ] && [ "$cells" != 0 ] && extra=(--initial-cells "$cells")
        $pelage sim --mesh "$mesh" --preset "$preset" --seed 1 "${extra[@]}" \
            -o scenes/gallery_$kind.cells >/dev/null
        $pelage stats scenes/gallery_$kind.cells --mesh "$mesh" --json >"$tmp/$name.$kind.json"
        $pelage render scenes/gallery_$kind.json -q -o "$tmp/g.exr" --preview "$tmp/g.png"
        oiiotool --create 240x202 3 \
            --text:x=6:y=196:size=14:color=1,1,1:font=$font "$name" -o "$tmp/label.png"
        oiiotool "$tmp/g.png" --ch R,G,B "$tmp/label.png" --paste +0+0 \
            -o "$tmp/tile_${kind}_$name.png"
        [ $kind = sphere ] && tiles_sphere+=("$tmp/tile_${kind}_$name.png")
        [ $kind = cow ] && tiles_cow+=("$tmp/tile_${kind}_$name.png")
    done
    python3 - "$preset" <<'PY' >scenes/gallery_cow_fur.json
import json, sys
preset = json.load(open(sys.argv[1]))
scene = json.load(open("scenes/gallery_cow.json"))
fur = json.load(open("scenes/fur_cow_giraffe.json"))["objects"][0]["fur"]
if preset.get("simulation", {}).get("anisotropy", {}).get("field"):
    fur.update({"comb": "field", "comb_towards": fur["comb"], "comb_jitter": 4})
scene["objects"][0]["fur"] = fur
print(json.dumps(scene, indent=1))
PY
    $pelage render scenes/gallery_cow_fur.json -q -o "$tmp/g.exr" --preview "$tmp/g.png"
    oiiotool --create 240x202 3 \
        --text:x=6:y=196:size=14:color=1,1,1:font=$font "$name" -o "$tmp/label.png"
    oiiotool "$tmp/g.png" --ch R,G,B "$tmp/label.png" --paste +0+0 -o "$tmp/tile_fur_$name.png"
    tiles_fur+=("$tmp/tile_fur_$name.png")
    [ $first = 1 ] || echo ',' >>"$tmp/gallery.json"
    first=0
    printf '"%s": {"sphere": %s, "cow": %s, "sphere_initial_cells": %s}' "$name" \
        "$(cat "$tmp/$name.sphere.json")" "$(cat "$tmp/$name.cow.json")" "$cells" \
        >>"$tmp/gallery.json"
done
echo '}' >>"$tmp/gallery.json"
rows=$(( (${#tiles_sphere[@]} + 3) / 4 ))
oiiotool "${tiles_sphere[@]}" --mosaic:pad=4 4x$rows -o images/gallery_sphere.png
oiiotool "${tiles_cow[@]}" --mosaic:pad=4 4x$rows -o images/gallery_cow.png
oiiotool "${tiles_fur[@]}" --mosaic:pad=4 4x$rows -o images/gallery_cow_fur.png
python3 - "$tmp/gallery.json" >docs/data/gallery.json <<'PY'
import json, os, sys
keep = ["cells", "cells_by_type", "spot_fraction", "spot_fraction_by_area", "spot_count",
        "spot_area_share_mean", "spot_neighbours_mean", "spot_complexity",
        "background_components", "background_largest_share", "background_near_spot"]
d = json.load(open(sys.argv[1]))
out = {}
for name, g in d.items():
    preset = json.load(open(os.path.join("scenes", "presets", name + ".json")))
    out[name] = {"published": preset.get("published", {}),
                 "sphere_initial_cells": g["sphere_initial_cells"],
                 "sphere": {k: g["sphere"][k] for k in keep},
                 "cow": {k: g["cow"][k] for k in keep}}
print(json.dumps({"gallery": out, "seed": 1}, indent=2, sort_keys=True))
PY
rm -f scenes/gallery_sphere.cells scenes/gallery_cow.cells scenes/gallery_cow_fur.json

# A rigged animal walking with its coat and fur: the Khronos sample fox (Fox.glb, CC-BY
# 4.0: model by PixelMannen, rigging and animation by @tomkranis, glTF by @AsoboStudio and
# @scurest), which the repository does not ship. PELAGE_FOX names the file; without it
# the fox's images stay as they are. Frames 200-247 of its one clip are the walk, blurred
# over half of each frame (a film camera's 180° shutter).
if [ -n "${PELAGE_FOX:-}" ] && [ -f "$PELAGE_FOX" ]; then
    $pelage look "$PELAGE_FOX" --clip "Armature|Take 001|BaseLayer" --frames 200-247 \
        --fur --shutter 0.5 --res 480x270 --spp 16 -q -o "$tmp/fox.exr"
    $pelage movie "$tmp/fox.####.exr" -q -o images/fox_walk.mp4
    strip=()
    for f in 0200 0206 0212 0218; do strip+=("$tmp/fox_preview.$f.png"); done
    oiiotool "${strip[@]}" --mosaic:pad=4 4x1 --resize 1440x0 -o images/fox_walk_strip.png
else
    echo "make_images.sh: PELAGE_FOX is not set: images/fox_walk.* left as they are" >&2
fi
echo "make_images.sh: images/*.png regenerated"
