#!/usr/bin/env bash
# ThreadSanitizer needs every library that synchronises threads to be instrumented:
# Debian's libtbb is not, so TSan cannot see the hand-off of a parallel_for's work to
# TBB's workers and reports every datum published before the loop as a race (hundreds of
# false reports per run, in TBB's own headers and in ours). This builds Debian 12's own
# oneTBB source (2021.8.0, the version libtbb-dev ships, checked against its SHA-256)
# with -fsanitize=thread, for the TSan suite to run against (LD_LIBRARY_PATH). Embree
# picks it up too (same soname, libtbb.so.12).
#   tests/tsan_tbb.sh DEST_DIR      → DEST_DIR/lib/libtbb.so.12
set -euo pipefail
dest="$(realpath -m "${1:?usage: tests/tsan_tbb.sh DEST_DIR}")"
[ -e "$dest/lib/libtbb.so.12" ] && exit 0
version=2021.8.0
sha256=7e9111b8bb59c8800bf6d0b06afe7b0891937443d2dae1ee1101c8e2ede6a7ef
work="$dest/src"
mkdir -p "$work"
tarball="$work/onetbb_$version.orig.tar.xz"
if [ ! -e "$tarball" ]; then
    curl -fsSL -o "$tarball.part" \
        "http://deb.debian.org/debian/pool/main/o/onetbb/onetbb_$version.orig.tar.xz"
    mv "$tarball.part" "$tarball"
fi
echo "$sha256  $tarball" | sha256sum -c --quiet
tar -xf "$tarball" -C "$work"
cmake -S "$work/oneTBB-$version" -B "$work/build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DTBB_SANITIZE=thread -DTBB_TEST=OFF -DTBB_EXAMPLES=OFF -DTBB_STRICT=OFF \
    -DTBBMALLOC_BUILD=OFF >/dev/null
cmake --build "$work/build" -j2 --target tbb
mkdir -p "$dest/lib"
cp -a "$work"/build/*_relwithdebinfo/libtbb.so* "$dest/lib/"
echo "tsan_tbb: $dest/lib/libtbb.so.12"
