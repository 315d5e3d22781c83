#!/usr/bin/env bash
# pelage quick start. On a fresh Debian 12 machine (as root, or with sudo):
#   ./quickstart.sh run    install what is missing, build, fetch sample meshes, grow a giraffe
#                          coat on the cow and render it (images/cow_giraffe.exr + preview PNG)
#   ./quickstart.sh test   the same set-up, then the whole test suite (ctest)
set -euo pipefail
cd "$(dirname "$0")"

mode="${1:-run}"
case "$mode" in run|test) ;; *) echo "usage: $0 [run|test]" >&2; exit 2 ;; esac

# --- Debian packages the project builds and runs with (kept in one place) ---
packages=(
    cmake g++ make pkg-config ca-certificates git python3
    clang-format         # tests: the style check (tests/style/check_style.py)
    libtbb-dev libtinyobjloader-dev nlohmann-json3-dev libcli11-dev libfmt-dev libxxhash-dev
    libembree-dev libopenimageio-dev openimageio-tools libopenexr-dev libopencolorio-dev
    libopencv-core-dev   # Debian's OpenImageIO CMake config names an opencv4 include folder
    libassimp-dev        # meshes: glTF, FBX, PLY, Collada, ... (sim/mesh/mesh_io_assimp.cpp)
    libgtest-dev libgmock-dev libbenchmark-dev
    libcgal-dev          # tests: the exact-geodesic oracle (tests/oracle)
    libeigen3-dev        # sparse Cholesky of the anisotropy fields (sim/field)
    ffmpeg               # pelage movie (encodes EXR sequences)
    fonts-dejavu-core    # labels of `pelage compare` contact sheets
    slurm-wlm munge      # tests: the farm recipe on a private Slurm cluster (tests/farm)
    libcpp-httplib-dev libjs-three   # pelage explore: its HTTP server and its page's 3D view
    chromium chromium-driver         # tests: the explorer's page in a headless browser
    nodejs               # tests: the independent USD and glTF readers (tests/export)
)
missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# npm comes with Debian's nodejs as its own package, or inside another nodejs build.
[ "$mode" = run ] || command -v npm >/dev/null || missing+=(npm)
if [ ${#missing[@]} -gt 0 ]; then
    echo "quickstart: installing ${missing[*]}"
    sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    $sudo apt-get update
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends "${missing[@]}"
fi

# --- Build (Release), two jobs: the reference machine has two cores ---
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j2

# --- Sample meshes from Debian's libcgal-demo (never committed) ---
scenes/fetch_meshes.sh

if [ "$mode" = run ]; then
    # The default job: a giraffe (reticulata) coat grown on the cow (the scene's "pattern",
    # kept in scenes/cow_giraffe.cells), rendered.
    build/bin/pelage render scenes/cow_giraffe.json -o images/cow_giraffe.exr \
        --stats-json build/cow_giraffe_render.json
    echo "quickstart: wrote images/cow_giraffe.exr and images/cow_giraffe_preview.png"
else
    # The exports' independent readers, pinned by tests/export/package-lock.json.
    mkdir -p build/npm
    cp tests/export/package.json tests/export/package-lock.json build/npm/
    npm ci --prefix build/npm --no-audit --no-fund --loglevel=error
    (cd build && ctest --output-on-failure -j2)
    # --- The input-handling tests again under ASan + UBSan (docs/guide/development.md): fuzz
    # corpus replays and the hostile/malformed CLI tables. The whole suite under ASan and
    # TSan is tests/nightly.sh (too long for CI on two cores).
    cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPELAGE_SANITIZE=ON
    cmake --build build-asan -j2 --target pelage fuzz_off fuzz_obj fuzz_ply fuzz_cells fuzz_scene fuzz_shader_params
    (cd build-asan && ctest -L asan --output-on-failure -j2)
fi
