#!/usr/bin/env bash
# Embree for the ThreadSanitizer suite. Debian's libembree3 is not instrumented, and
# Embree runs its BVH builds as TBB tasks whose hand-offs are TBB header code compiled
# into libembree3: TSan, even with an instrumented libtbb (tests/tsan_tbb.sh), then sees
# a worker touch the TBB bookkeeping Embree left on the caller's stack with no
# synchronisation after it, and reports pelage's next write to that stack as a race.
# This builds Debian 12's own Embree source (3.13.5, the version libembree-dev ships,
# checked against the SHA-256 in Debian's Sources index) with -fsanitize=thread against
# the system TBB headers, for the suite to load before Debian's (LD_LIBRARY_PATH; same
# soname, libembree3.so.3). SSE2 kernels and the geometry types pelage uses only: the
# build takes minutes instead of an hour, and what TSan checks (the threading) is the
# same for every ISA.
#   tests/tsan_embree.sh DEST_DIR      → DEST_DIR/lib/libembree3.so.3
set -euo pipefail
dest="$(realpath -m "${1:?usage: tests/tsan_embree.sh DEST_DIR}")"
[ -e "$dest/lib/libembree3.so.3" ] && exit 0
version=3.13.5
sha256=1b7c5b6144230ad81b92ece884a2017fbbb433bf5416a6fca9257e0109501c63
work="$dest/src"
mkdir -p "$work"
tarball="$work/embree_$version+dfsg.orig.tar.xz"
if [ ! -e "$tarball" ]; then
    curl -fsSL -o "$tarball.part" \
        "http://deb.debian.org/debian/pool/main/e/embree/embree_$version%2Bdfsg.orig.tar.xz"
    mv "$tarball.part" "$tarball"
fi
echo "$sha256  $tarball" | sha256sum -c --quiet
tar -xf "$tarball" -C "$work"
cmake -S "$work/embree-$version" -B "$work/build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_FLAGS=-fsanitize=thread -DCMAKE_CXX_FLAGS=-fsanitize=thread \
    -DCMAKE_SHARED_LINKER_FLAGS=-fsanitize=thread \
    -DEMBREE_TASKING_SYSTEM=TBB -DEMBREE_ISPC_SUPPORT=OFF -DEMBREE_TUTORIALS=OFF \
    -DEMBREE_MAX_ISA=SSE2 -DEMBREE_GEOMETRY_SUBDIVISION=OFF -DEMBREE_GEOMETRY_GRID=OFF \
    -DEMBREE_GEOMETRY_USER=OFF >/dev/null
cmake --build "$work/build" -j2 --target embree
mkdir -p "$dest/lib"
cp -a "$work"/build/libembree3.so* "$dest/lib/"
echo "tsan_embree: $dest/lib/libembree3.so.3"
