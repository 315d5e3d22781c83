#!/usr/bin/env bash
# Every scene in the bad-scene corpus must make `pelage render` exit with code 2 and a
# message naming the file and the JSON path (tests/data/bad_scenes/expected.tsv), and
# must not write the output or the stats.
set -u
pelage="$1"
corpus="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
failures=0
while IFS=$'\t' read -r file expected; do
    case "$file" in ''|'#'*) continue ;; esac
    "$pelage" render "$corpus/$file" -o "$tmp/out.exr" --stats-json "$tmp/stats.json" >"$tmp/out" 2>"$tmp/err"
    rc=$?
    if [ "$rc" -ne 2 ]; then
        echo "FAIL $file: exit code $rc, expected 2"; cat "$tmp/err"; failures=$((failures + 1)); continue
    fi
    if ! grep -qF -- "$expected" "$tmp/err"; then
        echo "FAIL $file: stderr lacks '$expected':"; cat "$tmp/err"; failures=$((failures + 1)); continue
    fi
    if [ -e "$tmp/out.exr" ] || [ -e "$tmp/stats.json" ]; then
        echo "FAIL $file: an output was written for a rejected scene"; failures=$((failures + 1))
    fi
    echo "ok   $file: $(head -n1 "$tmp/err")"
done < "$corpus/expected.tsv"

"$pelage" render >/dev/null 2>&1; rc=$?
[ "$rc" -eq 2 ] || { echo "FAIL: missing scene gave exit $rc"; failures=$((failures + 1)); }
"$pelage" render "$corpus/does_not_exist.json" -o "$tmp/o.exr" 2>"$tmp/err" >/dev/null; rc=$?
{ [ "$rc" -eq 2 ] && grep -qF "does_not_exist.json: cannot open scene file" "$tmp/err"; } ||
    { echo "FAIL: missing scene file gave exit $rc"; cat "$tmp/err"; failures=$((failures + 1)); }

[ "$failures" -eq 0 ] || { echo "$failures failure(s)"; exit 1; }
