#!/bin/bash
# An installation runs from wherever its prefix is moved: `cmake --install` into a
# temporary prefix, the prefix copied to a second place and the first removed, then,
# from a working folder outside both trees and with none of pelage's environment
# variables set: `pelage shaders`, `pelage sim` with a preset by name on a procedural
# mesh, `pelage render` of a clonal_mosaic scene with an OCIO view, and `pelage explore`
# serving its page and three.js. Nothing may come
# from the build or source tree: no installed file has either on its RPATH, the dynamic
# loader opens no file in them, and with a part of the installation taken away the
# command fails naming the installation's path instead of falling back to the sources.
# Then $PELAGE_DATA_DIR is searched before the installation's data.
# Usage: relocated_install.sh CMAKE BUILD_DIR SOURCE_DIR
set -u
cmake=$1
build=$(cd "$2" && pwd -P)
source=$(cd "$3" && pwd -P)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
unset PELAGE_DATA_DIR PELAGE_SHADER_PATH OCIO
failures=0
fail() {
    echo "FAIL: $*"
    failures=$((failures + 1))
}
# run NAME CMD...: CMD's exit code in $rc, its stdout and stderr in $work/NAME.{out,err}.
run() {
    local name=$1
    shift
    timeout 120 "$@" >"$work/$name.out" 2>"$work/$name.err"
    rc=$?
}

if ! "$cmake" --install "$build" --prefix "$work/first" >"$work/install.log" 2>&1; then
    cat "$work/install.log"
    echo "FAIL: cmake --install"
    exit 1
fi
cp -a "$work/first" "$work/moved"
rm -rf "$work/first"
prefix=$work/moved
pelage=$prefix/bin/pelage
mkdir "$work/cwd"
cd "$work/cwd" || exit 1

for f in bin/pelage lib/pelage/libpelage_cli.so lib/pelage/shaders/clonal_mosaic.so \
    lib/pelage/shaders/diffuse.so share/pelage/ocio/config.ocio \
    share/pelage/ocio/luts/filmic.spi1d share/pelage/scenes/presets/walter-cheetah.json \
    share/pelage/explore/index.html share/pelage/explore/explore.js \
    share/pelage/explore/three/build/three.module.js \
    share/pelage/explore/three/examples/jsm/controls/OrbitControls.js; do
    [ -s "$prefix/$f" ] || fail "$f is not installed"
done

while IFS= read -r -d '' f; do
    if head -c 4 "$f" | grep -q ELF; then
        paths=$(readelf -d "$f" | grep -E 'RPATH|RUNPATH')
        case $paths in
        *"$build"* | *"$source"*) fail "${f#"$prefix"/} has the build or source tree on its RPATH: $paths" ;;
        esac
    fi
done < <(find "$prefix" -type f -print0)

run version "$pelage" --version
[ "$rc" = 0 ] && grep -q '^pelage ' "$work/version.out" || fail "pelage --version: exit $rc"

# Every shared object the dynamic loader opens, the launcher's body and the plugins
# included, is the installation's or the system's.
LD_DEBUG=files run shaders "$pelage" shaders
[ "$rc" = 0 ] || fail "pelage shaders: exit $rc: $(tail -3 "$work/shaders.err")"
grep -q "file: $prefix/lib/pelage/shaders/clonal_mosaic.so" "$work/shaders.out" ||
    fail "pelage shaders does not list the installation's clonal_mosaic.so"
grep -q "file=$prefix/lib/pelage/libpelage_cli.so" "$work/shaders.err" ||
    fail "the installation's libpelage_cli.so was not loaded"
if grep -E "file=($build|$source)/" "$work/shaders.err" >"$work/leaks"; then
    fail "loaded from the build or source tree: $(head -3 "$work/leaks")"
fi

run sim "$pelage" sim --mesh procedural:sphere:12x12 --preset walter-cheetah --initial-cells 300 \
    --seed 1 -o coat.cells
[ "$rc" = 0 ] && [ -s coat.cells ] || fail "pelage sim: exit $rc: $(tail -3 "$work/sim.err")"

cat >scene.json <<'SCENE'
{
  "camera": {"position": [0, 0.4, 3.2], "look_at": [0, 0, 0], "fov": 40},
  "film": {"width": 48, "height": 32, "spp": 2, "output": "out/coat.exr",
           "preview": "out/coat.png", "view": "Filmic"},
  "lights": [{"type": "environment", "color": [0.6, 0.7, 0.9]},
             {"type": "distant", "direction": [-1, -1, -0.5], "angle": 1, "intensity": 2}],
  "objects": [{"mesh": "procedural:sphere:12x12", "cells": "coat.cells", "normals": "smooth",
               "material": {"shader": "clonal_mosaic", "bsdf": "coated"}}]
}
SCENE
mkdir out
run render "$pelage" render scene.json
[ "$rc" = 0 ] || fail "pelage render: exit $rc: $(tail -3 "$work/render.err")"
[ -s out/coat.exr ] || fail "pelage render wrote no EXR"
[ -s out/coat.png ] || fail "pelage render wrote no preview"

# `pelage explore` serves the installation's page and its copy of three.js.
timeout 60 "$pelage" explore procedural:sphere:12x12 --preset walter-cheetah --port 0 \
    >"$work/explore.out" 2>"$work/explore.err" &
explore_pid=$!
url=""
for _ in $(seq 100); do
    url=$(grep -o 'http://127.0.0.1:[0-9]*/' "$work/explore.out")
    [ -n "$url" ] && break
    sleep 0.1
done
if [ -z "$url" ]; then
    fail "pelage explore printed no URL: $(tail -3 "$work/explore.err")"
else
    python3 - "$url" <<'PY' || fail "pelage explore does not serve its page"
import sys, urllib.request
for path, needle in (("", b"pelage explore"), ("three/build/three.module.js", b"REVISION"),
                     ("three/examples/jsm/controls/OrbitControls.js", b"OrbitControls")):
    with urllib.request.urlopen(sys.argv[1] + path, timeout=10) as r:
        assert needle in r.read(), path
PY
fi
kill -INT "$explore_pid" 2>/dev/null
wait "$explore_pid"
rc=$?
[ "$rc" = 0 ] || fail "pelage explore did not stop cleanly on Ctrl-C: exit $rc"

# Without the installation's OCIO config or presets the command fails naming where they
# should have been: there is no copy in the source tree to fall back on.
mv "$prefix/share/pelage/ocio" "$work/ocio.away"
run render_no_ocio "$pelage" render scene.json
[ "$rc" != 0 ] && grep -q "$prefix/share/pelage/ocio/config.ocio" "$work/render_no_ocio.err" ||
    fail "render without share/pelage/ocio: exit $rc: $(tail -3 "$work/render_no_ocio.err")"
mv "$work/ocio.away" "$prefix/share/pelage/ocio"
mv "$prefix/share/pelage/scenes" "$work/scenes.away"
run sim_no_presets "$pelage" sim --mesh procedural:sphere:12x12 --preset walter-cheetah \
    --initial-cells 300 -o none.cells
[ "$rc" = 2 ] && grep -q "$prefix/share/pelage/scenes/presets" "$work/sim_no_presets.err" ||
    fail "sim without share/pelage/scenes: exit $rc: $(tail -3 "$work/sim_no_presets.err")"
[ -e none.cells ] && fail "sim without its preset wrote none.cells"
mv "$work/scenes.away" "$prefix/share/pelage/scenes"

# $PELAGE_DATA_DIR is searched first: a preset that exists only there.
mkdir -p "$work/data/scenes/presets"
cp "$prefix/share/pelage/scenes/presets/walter-cheetah.json" \
    "$work/data/scenes/presets/only-in-data-dir.json"
PELAGE_DATA_DIR=$work/data run sim_data_dir "$pelage" sim --mesh procedural:sphere:12x12 \
    --preset only-in-data-dir --initial-cells 300 --seed 1 -o data_dir.cells
[ "$rc" = 0 ] && cmp -s coat.cells data_dir.cells ||
    fail "sim with a preset from \$PELAGE_DATA_DIR: exit $rc: $(tail -3 "$work/sim_data_dir.err")"

if [ "$failures" != 0 ]; then
    echo "$failures failure(s)"
    exit 1
fi
echo "relocated install: all checks passed"
