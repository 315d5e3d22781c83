#!/usr/bin/env bash
# Hostile inputs (tests/data/hostile/expected.tsv): each row runs one pelage subcommand
# under a time limit and, unless SANITIZED=1 (ASan/TSan reserve terabytes of address
# space), a 4 GB address-space limit, then checks the exit code, that stderr contains the
# expected substring, and that a rejected input leaves no output file behind while an
# accepted one writes it.
#   hostile_inputs.sh PELAGE CORPUS_DIR
set -u
pelage="$1"
corpus="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
time_limit="${HOSTILE_TIME_LIMIT:-60}"
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }

# --- Inputs made at test time (never committed) ---
gen="$tmp/gen"
mkdir -p "$gen"
# A 1 GB line: a sparse file, so it costs no disk; readers must stop after 1 MiB.
printf 'OFF\n' > "$gen/long_line.off" && truncate -s 1G "$gen/long_line.off"
printf 'v 0 0 0\nv 1 0 0\n' > "$gen/long_line.obj" && truncate -s 1G "$gen/long_line.obj"
# JSON nested 100 000 deep, closed and unclosed.
depth=100000
{ printf '{"camera": '; head -c $depth /dev/zero | tr '\0' '['; head -c $depth /dev/zero | tr '\0' ']'
  printf ', "film": {"width": 16, "height": 16}, "objects": []}\n'; } > "$gen/deeply_nested.json"
head -c $depth /dev/zero | tr '\0' '[' > "$gen/deeply_nested_unclosed.json"
# Unicode file names (UTF-8), valid and invalid content.
cp "$corpus/single_triangle.off" "$gen/maillé_ünïcode_猫.off"
cp "$corpus/truncated.off" "$gen/truncated_ünïcode_猫.off"

while IFS=$'\t' read -r file command expected_rc expected gen_flag; do
    case "$file" in ''|'#'*) continue ;; esac
    dir="$corpus"
    [ "${gen_flag:-}" = "@gen" ] && dir="$gen"
    in="$dir/$file"
    rm -f "$tmp/out" "$tmp/out.exr" "$tmp/stats.json"
    case "$command" in
        crps) args=(crps --mesh "$in" --stats-json "$tmp/stats.json"); out="$tmp/stats.json" ;;
        sim) args=(sim --mesh "$in" --preset teo-cheetah --initial-cells 30 --seed 1 -o "$tmp/out"
                   --stats-json "$tmp/stats.json"); out="$tmp/out" ;;
        preset) args=(sim --mesh procedural:sphere:6x6 --preset "$in" -o "$tmp/out"
                      --stats-json "$tmp/stats.json"); out="$tmp/out" ;;
        stats) args=(stats "$in" --stats-json "$tmp/stats.json"); out="$tmp/stats.json" ;;
        render) args=(render "$in" -q -o "$tmp/out.exr" --stats-json "$tmp/stats.json"); out="$tmp/out.exr" ;;
        *) fail "$file: unknown command '$command' in the table"; continue ;;
    esac
    start=$(date +%s%N)
    (
        [ "${SANITIZED:-0}" = 1 ] || ulimit -v 4000000
        exec timeout "$time_limit" "$pelage" "${args[@]}"
    ) >"$tmp/stdout" 2>"$tmp/err"
    rc=$?
    ms=$((($(date +%s%N) - start) / 1000000))
    if [ "$rc" -eq 124 ]; then fail "$file: no answer within ${time_limit}s"; continue; fi
    if [ "$rc" -ne "$expected_rc" ]; then
        fail "$file: exit code $rc, expected $expected_rc"; cat "$tmp/err"; continue
    fi
    if [ "$expected" != "-" ] && ! grep -qF -- "$expected" "$tmp/err"; then
        fail "$file: stderr lacks '$expected':"; cat "$tmp/err"; continue
    fi
    if [ "$expected_rc" -ne 0 ] && { [ -e "$tmp/out" ] || [ -e "$tmp/out.exr" ] || [ -e "$tmp/stats.json" ]; }; then
        fail "$file: an output was written for a rejected input"; continue
    fi
    if [ "$expected_rc" -eq 0 ] && [ ! -s "$out" ]; then
        fail "$file: accepted, but no output was written"; continue
    fi
    echo "ok   $file ($command, exit $rc, ${ms} ms): $(head -n1 "$tmp/err")"
done < "$corpus/expected.tsv"

[ "$failures" -eq 0 ] || { echo "$failures failure(s)"; exit 1; }
