#!/usr/bin/env bash
# The nightly hardening run; too long for CI, which runs the ASan +
# UBSan input-handling subset only (quickstart.sh test). Run from anywhere:
#   tests/nightly.sh [FUZZ_SECONDS]        (default 300 s per fuzz target)
# 1. the whole suite under AddressSanitizer + UndefinedBehaviorSanitizer (build-asan);
# 2. the whole suite under ThreadSanitizer (build-tsan, against a TSan-instrumented
#    libtbb built by tests/tsan_tbb.sh; suppressions in tests/tsan.supp);
# 3. the libFuzzer targets (clang, build-fuzz): corpus replay, then FUZZ_SECONDS each.
# Any sanitizer report fails the run (ASan/UBSan abort; TSan exits 66).
set -euo pipefail
cd "$(dirname "$0")/.."
fuzz_seconds="${1:-300}"
export CCACHE_BASEDIR="$PWD"
# What the nightly run needs beyond quickstart.sh's packages: clang + libFuzzer, and curl
# for Debian's oneTBB source (tests/tsan_tbb.sh).
extra=(clang-14 libclang-rt-14-dev curl xz-utils)
missing=()
for p in "${extra[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
    sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    $sudo apt-get update
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends "${missing[@]}"
fi
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
scenes/fetch_meshes.sh

echo "== ASan + UBSan: whole suite"
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPELAGE_SANITIZE=ON "${launcher[@]}"
cmake --build build-asan -j2
(cd build-asan && ctest -j2 --output-on-failure)

echo "== TSan: whole suite"
cmake -S . -B build-tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPELAGE_TSAN=ON "${launcher[@]}"
cmake --build build-tsan -j2
tests/tsan_tbb.sh build-tsan/tbb   # an instrumented libtbb: see the script for why
(cd build-tsan && LD_LIBRARY_PATH="$PWD/tbb/lib" \
    TSAN_OPTIONS="suppressions=$PWD/../tests/tsan.supp history_size=7 halt_on_error=1 exitcode=66" \
    ctest -j2 --output-on-failure)

echo "== libFuzzer: replay, then ${fuzz_seconds}s per target"
cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang \
    -DCMAKE_CXX_COMPILER=clang++ -DPELAGE_FUZZ=ON "${launcher[@]}"
targets=(off obj cells scene shader_params)
cmake --build build-fuzz -j2 --target "${targets[@]/#/fuzz_}"
for t in "${targets[@]}"; do
    build-fuzz/bin/fuzz_$t -runs=0 tests/fuzz/corpus/$t tests/fuzz/crashes/$t
done
rm -rf build-fuzz/fuzz-artifacts
tests/fuzz/run_fuzzers.sh "$fuzz_seconds"
if compgen -G "build-fuzz/fuzz-artifacts/*/crash-*" >/dev/null ||
   compgen -G "build-fuzz/fuzz-artifacts/*/leak-*" >/dev/null ||
   compgen -G "build-fuzz/fuzz-artifacts/*/timeout-*" >/dev/null; then
    echo "nightly: the fuzzers found something: build-fuzz/fuzz-artifacts/"; exit 1
fi
echo "nightly: all clean"
