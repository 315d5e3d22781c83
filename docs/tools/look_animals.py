#!/usr/bin/env python3
"""From a mesh to a picture: `pelage look MESH --res 480x270 --spp 16` on every animal of
Debian's libcgal-demo and assimp-testmodels, the Khronos fox when PELAGE_FOX names it,
the cow split at its edge midpoints four times (1.5 M triangles, written here as a
binary PLY) and the cow cut into a triangle soup (pieces of 24 triangles, none sharing a
vertex). Prints JSON: per mesh the wall time, peak resident memory, the cells grown, the
growth's seconds, the render's set-up, the share of the animal's pixels without a cell,
and, where the head is known, whether the view faces it. Each run is a separate process, all cores.

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
    # Not NAME.json: look writes its scene there, beside the EXR.
    stats = os.path.join(work, name + ".stats.json")
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


def soup(path, piece=24, offset=1e-4, seed=1):
    """cow.off as an asset store's triangle soup: pieces of about `piece` triangles grown
    over shared edges, each with its own copies of its vertices moved by up to `offset`
    of the bounding-box diagonal (an export's per-part rounding), so no piece shares a
    vertex with another."""
    import random
    rng = random.Random(seed)
    verts, faces = read_off("scenes/meshes/cow.off")
    lo = [min(v[k] for v in verts) for k in range(3)]
    hi = [max(v[k] for v in verts) for k in range(3)]
    diag = sum((h - l) ** 2 for h, l in zip(hi, lo)) ** 0.5
    by_edge = {}
    for i, f in enumerate(faces):
        for a, b in ((f[0], f[1]), (f[1], f[2]), (f[2], f[0])):
            by_edge.setdefault((min(a, b), max(a, b)), []).append(i)
    piece_of = [-1] * len(faces)
    pieces = []
    for start in range(len(faces)):
        if piece_of[start] >= 0:
            continue
        members, queue = [], [start]
        piece_of[start] = len(pieces)
        while queue and len(members) < piece:
            i = queue.pop(0)
            members.append(i)
            f = faces[i]
            for a, b in ((f[0], f[1]), (f[1], f[2]), (f[2], f[0])):
                for j in by_edge[(min(a, b), max(a, b))]:
                    if piece_of[j] < 0 and len(members) + len(queue) < piece:
                        piece_of[j] = len(pieces)
                        queue.append(j)
        for i in queue:  # reserved but not reached: their own pieces later
            piece_of[i] = -1
        pieces.append(members)
    out_v, out_f = [], []
    for members in pieces:
        shift = [rng.uniform(-offset, offset) * diag for _ in range(3)]
        local = {}
        for i in members:
            tri = []
            for v in faces[i]:
                if v not in local:
                    local[v] = len(out_v)
                    out_v.append(tuple(c + d for c, d in zip(verts[v], shift)))
                tri.append(local[v])
            out_f.append(tuple(tri))
    write_ply(path, out_v, out_f)
    return len(pieces)


# Where each mesh's head is (found by eye on side views; docs/guide/look.md's table): the
# axis and its sign. The view faces the head when the camera stands on that side.
HEADS = {"cow": (0, 1), "bull": (0, -1), "camel": (2, 1), "diplodocus": (0, 1),
         "elephant": (0, 1), "triceratops": (0, 1), "WusonOBJ.obj": (2, -1),
         "duck.dae": (0, 1), "cow as a triangle soup": (0, 1),
         "cow split 4 times": (0, 1)}


def no_cell_share(exr):
    """The share of the animal's pixels (id.object 0) whose shader.cell_id is -1."""
    def channel(name):
        tmp = exr + "." + name + ".exr"
        subprocess.run(["oiiotool", exr, "--ch", name, "-o", tmp], check=True)
        dump = subprocess.run(["oiiotool", "--dumpdata", tmp], capture_output=True,
                              text=True, check=True).stdout
        os.remove(tmp)
        return [float(line.split(":")[1]) for line in dump.splitlines() if "Pixel" in line]
    cells = [c for o, c in zip(channel("id.object"), channel("shader.cell_id")) if o == 0]
    return round(sum(1 for c in cells if c < 0) / max(1, len(cells)), 5)


def faces_head(scene, head):
    camera = json.load(open(scene))["camera"]
    axis, sign = head
    return (camera["position"][axis] - camera["look_at"][axis]) * sign > 0


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
    soup_path = os.path.join(work, "cow_soup.ply")
    soup(soup_path)
    meshes.append(("cow as a triangle soup", soup_path, "cow.off, pieces of 24 offset 1e-4"))
    runs = []
    for name, path, source in meshes:
        if not os.path.isfile(path):
            continue
        print("look_animals: " + name, file=sys.stderr)
        run = look(pelage, path, work, re.sub(r"\W", "_", name))
        run.update({"mesh": name, "source": source})
        base = os.path.join(work, re.sub(r"\W", "_", name))
        if run.get("exit_code") == 0:
            run["pixels_without_cell"] = no_cell_share(base + ".exr")
            if name in HEADS:
                run["faces_head"] = faces_head(base + ".json", HEADS[name])
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
