#!/usr/bin/env bash
# Runs the libFuzzer targets one after another, each for SECONDS (default 600), niced, on
# one core. The corpus grows in build-fuzz/corpus/<target>/ (seeded from the committed
# tests/fuzz/corpus/<target>/); to commit what it found, minimise it into the seeds:
#   build-fuzz/bin/fuzz_<t> -merge=1 tests/fuzz/corpus/<t> build-fuzz/corpus/<t>
# Crashes land in build-fuzz/fuzz-artifacts/<target>/; copy the reproducer to
# tests/fuzz/crashes/<target>/ with the fix, so CI replays it forever.
#   cmake -S . -B build-fuzz -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DPELAGE_FUZZ=ON
#   cmake --build build-fuzz -j2 --target fuzz_off fuzz_obj fuzz_ply fuzz_cells fuzz_scene fuzz_shader_params
#   tests/fuzz/run_fuzzers.sh [SECONDS] [TARGET...]
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds="${1:-600}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(off obj ply cells scene shader_params)
declare -A dict=([off]=off [obj]=obj [scene]=json [shader_params]=json)
for t in "${targets[@]}"; do
    mkdir -p "build-fuzz/fuzz-artifacts/$t" "build-fuzz/corpus/$t"
    args=(-max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -print_final_stats=1
          -artifact_prefix="build-fuzz/fuzz-artifacts/$t/")
    [ -n "${dict[$t]:-}" ] && args+=(-dict="tests/fuzz/dict/${dict[$t]}.dict")
    echo "== fuzz_$t for ${seconds}s"
    nice -n 19 "build-fuzz/bin/fuzz_$t" "${args[@]}" "build-fuzz/corpus/$t" "tests/fuzz/corpus/$t" \
        2>&1 | tee "build-fuzz/fuzz-artifacts/$t.log" | grep -E "^#[0-9]+ +(DONE|INITED)|ERROR|SUMMARY|stat::" || true
done
