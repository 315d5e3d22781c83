#!/usr/bin/env python3
"""From a mesh to a picture: `pelage look MESH --res 480x270 --spp 16` on every animal of
Debian's libcgal-demo and assimp-testmodels, the Khronos fox when PELAGE_FOX names it,
and the cow split at its edge midpoints four times (1.5 M triangles, written here as a
binary PLY). Prints JSON: per mesh the wall time, peak resident memory, the cells grown,
the growth's seconds and the render's set-up. Each run is a separate process, all cores.

Usage: look_animals.py PELAGE WORKDIR   (run from the repository; by run_benchmarks.sh)
"""
import json
import os
import re
import struct
import subprocess
import sys
import time

CGAL = ["armadillo", "bear", "bull", "bunny00", "camel", "cow", "dino", "diplodocus",
        "elephant", "elephant-with-holes", "elk", "lion", "pig", "refined_elephant",
        "triceratops"]
ASSIMP = ["Collada/duck.dae", "SIB/heffalump.sib", "OBJ/WusonOBJ.obj", "OBJ/spider.obj"]
TIMEOUT = 600


def read_off(path):
    words = " ".join(line.split("#")[0] for line in open(path)).split()
    nv, nf = int(words[1]), int(words[2])
    at = 4
    verts = [tuple(map(float, words[at + 3 * i:at + 3 * i + 3])) for i in range(nv)]
    at += 3 * nv
    faces = []
    for _ in range(nf):
        k = int(words[at])
        faces.append(tuple(int(w) for w in words[at + 1:at + 1 + k]))
        at += 1 + k
    return verts, faces


def split_midpoints(verts, faces):
    verts = list(verts)
    middle = {}

    def mid(a, b):
        key = (a, b) if a < b else (b, a)
        if key not in middle:
            pa, pb = verts[a], verts[b]
            middle[key] = len(verts)
            verts.append(((pa[0] + pb[0]) / 2, (pa[1] + pb[1]) / 2, (pa[2] + pb[2]) / 2))
        return middle[key]

    out = []
    for a, b, c in faces:
        ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
        out += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
    return verts, out


def write_ply(path, verts, faces):
    with open(path, "wb") as f:
        f.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\n"
                 "property float x\nproperty float y\nproperty float z\n"
                 "element face %d\nproperty list uchar int vertex_indices\nend_header\n"
                 % (len(verts), len(faces))).encode())
        f.write(b"".join(struct.pack("<3f", *v) for v in verts))
        f.write(b"".join(struct.pack("<B3i", 3, *t) for t in faces))


def look(pelage, mesh, work, name):
    stats = os.path.join(work, name + ".json")
    log = os.path.join(work, name + ".log")
    cmd = ["nice", "-n", "19", pelage, "look", mesh, "--res", "480x270", "--spp", "16",
           "-o", os.path.join(work, name + ".exr"), "--stats-json", stats]
    t0 = time.monotonic()
    with open(log, "w") as err:
        proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=err)
    # os.wait4 gives this child's own peak memory (nice execs pelage in its place).
    while True:
        pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
        if pid:
            break
        if time.monotonic() - t0 > TIMEOUT:
            proc.kill()
            os.wait4(proc.pid, 0)
            return {"timeout_seconds": TIMEOUT}
        time.sleep(0.05)
    wall = time.monotonic() - t0
    code = os.waitstatus_to_exitcode(status)
    err = open(log).read()
    run = {"exit_code": code, "wall_seconds": round(wall, 2),
           "peak_rss_mb": round(usage.ru_maxrss / 1024)}
    if code != 0:
        run["error"] = err.strip().splitlines()[-1] if err.strip() else ""
        return run
    st = json.load(open(stats))
    run.update({"setup_seconds": round(st["setup_seconds"], 2),
                "render_seconds": round(st["seconds"], 2),
                "rendered_triangles": st["triangles"]})
    grown = re.search(r"\.cells: (\d+) cells, ([\d.]+) s", err)
    if grown:
        run["cells"], run["growth_seconds"] = int(grown.group(1)), float(grown.group(2))
    return run


def main():
    pelage, work = sys.argv[1], sys.argv[2]
    meshes = [(n, "scenes/meshes/%s.off" % n, "libcgal-demo") for n in CGAL]
    meshes += [(os.path.basename(p), "/usr/share/assimp/models/" + p, "assimp-testmodels")
               for p in ASSIMP]
    fox = os.environ.get("PELAGE_FOX", "")
    if fox and os.path.isfile(fox):
        meshes.append(("Fox.glb", fox, "Khronos glTF samples"))
    # In a process of its own: a child forked from this one would count the split
    # mesh's memory as its own peak.
    dense = os.path.join(work, "cow_split4.ply")
    subprocess.run([sys.executable, __file__, "--split-cow", dense], check=True)
    meshes.append(("cow split 4 times", dense, "cow.off, midpoints"))
    runs = []
    for name, path, source in meshes:
        if not os.path.isfile(path):
            continue
        print("look_animals: " + name, file=sys.stderr)
        run = look(pelage, path, work, re.sub(r"\W", "_", name))
        run.update({"mesh": name, "source": source})
        runs.append(run)
    print(json.dumps({"res": "480x270", "spp": 16, "runs": runs}, indent=2))


def split_cow(path):
    verts, faces = read_off("scenes/meshes/cow.off")
    for _ in range(4):
        verts, faces = split_midpoints(verts, faces)
    write_ply(path, verts, faces)


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--split-cow":
        split_cow(sys.argv[2])
    else:
        main()
