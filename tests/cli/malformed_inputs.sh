#!/usr/bin/env bash
# Every file in the malformed corpus must make `pelage crps` exit with code 2 and a
# message naming the file, the line and the problem (tests/data/malformed/expected.tsv).
# Also checks that --stats-json is not written when the input is rejected.
set -u
pelage="$1"
corpus="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
failures=0
while IFS=$'\t' read -r file expected; do
    case "$file" in ''|'#'*) continue ;; esac
    "$pelage" crps --mesh "$corpus/$file" --stats-json "$tmp/stats.json" >"$tmp/out" 2>"$tmp/err"
    rc=$?
    if [ "$rc" -ne 2 ]; then
        echo "FAIL $file: exit code $rc, expected 2"; cat "$tmp/err"; failures=$((failures + 1)); continue
    fi
    if ! grep -qF -- "$expected" "$tmp/err"; then
        echo "FAIL $file: stderr lacks '$expected':"; cat "$tmp/err"; failures=$((failures + 1)); continue
    fi
    if [ -e "$tmp/stats.json" ]; then
        echo "FAIL $file: --stats-json was written for a rejected input"; failures=$((failures + 1))
    fi
    echo "ok   $file: $(head -n1 "$tmp/err")"
done < "$corpus/expected.tsv"

# Bad usage is exit 2 too.
"$pelage" crps >/dev/null 2>&1; rc=$?
[ "$rc" -eq 2 ] || { echo "FAIL: missing --mesh gave exit $rc"; failures=$((failures + 1)); }
"$pelage" frobnicate >/dev/null 2>&1; rc=$?
[ "$rc" -eq 2 ] || { echo "FAIL: unknown subcommand gave exit $rc"; failures=$((failures + 1)); }
"$pelage" crps --mesh procedural:sphere:1x1 >/dev/null 2>&1; rc=$?
[ "$rc" -eq 2 ] || { echo "FAIL: bad procedural spec gave exit $rc"; failures=$((failures + 1)); }
"$pelage" crps --help >/dev/null 2>&1; rc=$?
[ "$rc" -eq 0 ] || { echo "FAIL: --help gave exit $rc"; failures=$((failures + 1)); }

[ "$failures" -eq 0 ] || { echo "$failures failure(s)"; exit 1; }
