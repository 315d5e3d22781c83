#!/usr/bin/env bash
# Regenerates every PNG in images/ that the READMEs show, from this repository's scenes
# and presets, so the pictures always match the code that made them. Needs the build
# and the sample meshes (./quickstart.sh run). A few minutes on two cores.
set -euo pipefail
cd "$(dirname "$0")/.."
pelage=build/bin/pelage
if [ ! -x "$pelage" ] || [ ! -f scenes/meshes/cow.off ]; then
    echo "make_images.sh: run ./quickstart.sh run first (build and sample meshes)" >&2
    exit 2
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The mosaics the scenes read.
$pelage sim --mesh scenes/meshes/cow.off --preset giraffe-reticulata --seed 1 \
    -o build/cow_giraffe.cells
$pelage sim --mesh procedural:sphere:20x20 --preset teo-cheetah -o build/sphere_cheetah.cells
$pelage sim --mesh scenes/meshes/triceratops.off --preset teo-leopard \
    -o build/triceratops_leopard.cells

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
# The simulation alone: every cell a dot (pelage preview).
$pelage sim --mesh scenes/meshes/cow.off --preset giraffe-reticulata --cells 3000 --seed 1 \
    -o "$tmp/cow3000.cells"
$pelage preview "$tmp/cow3000.cells" -o images/sim_cow_giraffe_reticulata.png --size 480
echo "make_images.sh: images/*.png regenerated"
