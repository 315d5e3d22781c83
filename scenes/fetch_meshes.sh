#!/usr/bin/env bash
# Brings the sample meshes (cow, triceratops, lion, elephant, camel, bull, bunny00, ...)
# from Debian's libcgal-demo package into scenes/meshes/ (ignored by git; never commit
# them). Safe to run again: does nothing once the meshes are there.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
dest="$here/meshes"
archive=/usr/share/doc/libcgal-dev/data.tar.gz

if [ -f "$dest/cow.off" ] && [ -f "$dest/bunny00.off" ]; then
    exit 0
fi
if [ ! -f "$archive" ]; then
    echo "fetch_meshes: installing libcgal-demo (sample meshes)"
    sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    $sudo apt-get update
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends libcgal-demo
fi
mkdir -p "$dest"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
tar -xzf "$archive" -C "$tmp" --wildcards 'data/meshes/*.off'
mv "$tmp"/data/meshes/*.off "$dest"/
echo "fetch_meshes: $(ls "$dest"/*.off | wc -l) meshes in $dest"
