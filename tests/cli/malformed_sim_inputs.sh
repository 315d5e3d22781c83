#!/usr/bin/env bash
# Bad presets (tests/data/malformed_presets/expected.tsv) make `pelage sim` exit 2 with a
# message naming the file and the JSON path, and write nothing. Corrupted .cells files
# (made here from a fresh run: truncated, bad magic, wrong version, flipped byte, padded)
# make `pelage stats` and `pelage preview` exit 2, and a .cells file is never half-written.
set -u
pelage="$1"
corpus="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }

while IFS=$'\t' read -r file expected; do
    case "$file" in ''|'#'*) continue ;; esac
    "$pelage" sim --mesh procedural:sphere:6x6 --preset "$corpus/$file" -o "$tmp/x.cells" \
        --stats-json "$tmp/x.json" >"$tmp/out" 2>"$tmp/err"
    rc=$?
    if [ "$rc" -ne 2 ]; then fail "$file: exit code $rc, expected 2"; cat "$tmp/err"; continue; fi
    grep -qF -- "$file" "$tmp/err" || { fail "$file: stderr does not name the file"; cat "$tmp/err"; continue; }
    grep -qF -- "$expected" "$tmp/err" || { fail "$file: stderr lacks '$expected':"; cat "$tmp/err"; continue; }
    [ -e "$tmp/x.cells" ] && fail "$file: .cells written for a rejected preset"
    [ -e "$tmp/x.json" ] && fail "$file: --stats-json written for a rejected preset"
    echo "ok   $file: $(head -n1 "$tmp/err")"
done < "$corpus/expected.tsv"

# --- Unknown preset name, bad --relax ---
"$pelage" sim --mesh procedural:sphere:6x6 --preset no-such-preset >/dev/null 2>"$tmp/err"; rc=$?
[ "$rc" -eq 2 ] && grep -q "no-such-preset" "$tmp/err" || fail "unknown preset: exit $rc"
"$pelage" sim --mesh procedural:sphere:6x6 --preset teo-table-7.2 --relax sideways >/dev/null 2>&1; rc=$?
[ "$rc" -eq 2 ] || fail "bad --relax: exit $rc"

# --- Corrupted .cells ---
"$pelage" sim --mesh procedural:sphere:8x8 --preset teo-table-7.2 --initial-cells 300 -o "$tmp/good.cells" >/dev/null \
    || { fail "could not make a .cells file"; exit 1; }
size=$(stat -c %s "$tmp/good.cells")
head -c 50 "$tmp/good.cells" > "$tmp/short_header.cells"
head -c $((size / 2)) "$tmp/good.cells" > "$tmp/truncated.cells"
head -c $((size - 1)) "$tmp/good.cells" > "$tmp/no_checksum_byte.cells"
{ cat "$tmp/good.cells"; printf 'x'; } > "$tmp/padded.cells"
{ printf 'NOTCELLS'; tail -c +9 "$tmp/good.cells"; } > "$tmp/bad_magic.cells"
{ head -c 8 "$tmp/good.cells"; printf '\x07\x00\x00\x00'; tail -c +13 "$tmp/good.cells"; } > "$tmp/version7.cells"
cp "$tmp/good.cells" "$tmp/flipped.cells"
printf '\xff' | dd of="$tmp/flipped.cells" bs=1 seek=$((size / 2)) conv=notrunc status=none
: > "$tmp/empty.cells"
for case in short_header:truncated truncated:file\ size no_checksum_byte:file\ size padded:file\ size \
            bad_magic:not\ a\ .cells\ file version7:unsupported\ version flipped:checksum empty:truncated; do
    name="${case%%:*}"; want="${case#*:}"
    "$pelage" stats "$tmp/$name.cells" --json >"$tmp/out" 2>"$tmp/err"; rc=$?
    if [ "$rc" -ne 2 ]; then fail "$name.cells: stats exit $rc"; cat "$tmp/err"; continue; fi
    grep -qF "$name.cells" "$tmp/err" && grep -qF "$want" "$tmp/err" || { fail "$name.cells: stderr lacks '$want'"; cat "$tmp/err"; continue; }
    "$pelage" preview "$tmp/$name.cells" -o "$tmp/p.png" >/dev/null 2>&1; rc=$?
    [ "$rc" -eq 2 ] || fail "$name.cells: preview exit $rc"
    [ -e "$tmp/p.png" ] && fail "$name.cells: preview wrote a PNG"
    echo "ok   $name.cells: $(head -n1 "$tmp/err")"
done
"$pelage" stats "$tmp/good.cells" --json >/dev/null 2>&1 || fail "good.cells rejected"
"$pelage" stats "$tmp/good.cells" --mesh procedural:sphere:8x8 >/dev/null 2>&1 || fail "good.cells rejected with its own mesh"
"$pelage" stats "$tmp/good.cells" --mesh procedural:torus:24x12 >/dev/null 2>"$tmp/err"; rc=$?
[ "$rc" -eq 2 ] && grep -q "grown on another surface" "$tmp/err" || { fail "wrong mesh: exit $rc"; cat "$tmp/err"; }

[ "$failures" -eq 0 ] || { echo "$failures failure(s)"; exit 1; }
