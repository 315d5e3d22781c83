#!/usr/bin/env python3
"""`pelage bake --glb` loaded by three.js (Debian's libjs-three, its GLTFLoader) in
headless Chromium: the file parses into one textured mesh of the baked mesh's triangles,
the browser decodes the PNG inside and three.js reads it as sRGB, the texture sampled at
the mesh's own UVs is the bake encoded as sRGB (the EXR read by oiiotool), and a WebGL
frame of it draws the animal. The page is served on loopback by a server started and
stopped here; every wait is bounded. Usage: glb_three_test.py PELAGE. Exit 77 (skipped)
when Chromium or its driver is missing."""
import functools
import http.server
import json
import os
import re
import subprocess
import sys
import tempfile
import threading

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "explore"))
import webdriver  # noqa: E402

MESH = "procedural:sphere:16x12"
THREE = "/usr/share/javascript/three"
SIZE = 128

PAGE = """<!doctype html><html><body><script type="module">
import * as THREE from '/three/build/three.module.js';
import { GLTFLoader } from '/three/examples/jsm/loaders/GLTFLoader.js';
new GLTFLoader().load('coat.glb', (gltf) => {
  const meshes = [];
  gltf.scene.traverse((o) => { if (o.isMesh) meshes.push(o); });
  const m = meshes[0], g = m.geometry, map = m.material.map, img = map.image;
  // The texture as the browser decoded it, sampled at every vertex's UV (glTF's UVs:
  // (0, 0) is the image's top-left texel; three.js keeps flipY off for glTF).
  const c = document.createElement('canvas');
  c.width = img.width; c.height = img.height;
  const ctx = c.getContext('2d');
  ctx.drawImage(img, 0, 0);
  const px = ctx.getImageData(0, 0, c.width, c.height).data;
  const uv = g.attributes.uv, samples = [];
  for (let i = 0; i < uv.count; ++i) {
    const x = Math.min(c.width - 1, Math.floor(uv.getX(i) * c.width));
    const y = Math.min(c.height - 1, Math.floor(uv.getY(i) * c.height));
    const k = 4 * (y * c.width + x);
    samples.push([x, y, px[k], px[k + 1], px[k + 2]]);
  }
  // One WebGL frame of it, lit, framed on its bounding sphere.
  const scene = new THREE.Scene();
  scene.add(gltf.scene);
  scene.add(new THREE.AmbientLight(0xffffff, 0.6));
  const sun = new THREE.DirectionalLight(0xffffff, 0.8);
  sun.position.set(1, 2, 3);
  scene.add(sun);
  g.computeBoundingSphere();
  const s = g.boundingSphere;
  const camera = new THREE.PerspectiveCamera(40, 1, 0.01 * s.radius, 100 * s.radius);
  camera.position.copy(s.center).add(new THREE.Vector3(0, 0, 3.2 * s.radius));
  camera.lookAt(s.center);
  const r = new THREE.WebGLRenderer({ preserveDrawingBuffer: true });
  r.setSize(200, 200);
  r.render(scene, camera);
  const o = document.createElement('canvas');
  o.width = 200; o.height = 200;
  const og = o.getContext('2d');
  og.drawImage(r.domElement, 0, 0);
  const d = og.getImageData(0, 0, 200, 200).data;
  let drawn = 0;
  for (let i = 0; i < d.length; i += 4) if (d[i] + d[i + 1] + d[i + 2] > 30) ++drawn;
  window.result = {
    meshes: meshes.length, vertices: g.attributes.position.count,
    indices: g.index ? g.index.count : 0, normals: !!g.attributes.normal,
    srgb: map.encoding === THREE.sRGBEncoding, flipY: map.flipY,
    width: img.width, height: img.height, samples, drawn, pixels: 200 * 200 };
}, undefined, (e) => { window.result = { error: String(e && e.message || e) }; });
</script></body></html>
"""


class Handler(http.server.SimpleHTTPRequestHandler):
    """The page's folder, and Debian's three.js under /three/."""

    def translate_path(self, path):
        path = path.split("?", 1)[0]
        if path.startswith("/three/"):
            return os.path.join(THREE, os.path.normpath(path[len("/three/"):]))
        return super().translate_path(path)

    def log_message(self, *args):
        pass


def srgb_byte(linear):
    c = min(1.0, max(0.0, linear))
    e = 12.92 * c if c <= 0.0031308 else 1.055 * c ** (1 / 2.4) - 0.055
    return round(e * 255)


def run(*args):
    r = subprocess.run(args, capture_output=True, text=True, timeout=300)
    if r.returncode != 0:
        raise AssertionError(f"{' '.join(args)}: exit {r.returncode}: {r.stderr}")
    return r.stdout


def check(condition, message):
    if not condition:
        raise AssertionError(message)


def main(pelage):
    if not webdriver.browser_available():
        print("skipped: chromium or chromium-driver is not installed")
        return 77
    with tempfile.TemporaryDirectory() as tmp:
        cells = os.path.join(tmp, "coat.cells")
        run(pelage, "sim", "--mesh", MESH, "--preset", "teo-cheetah", "--seed", "3",
            "--initial-cells", "400", "-q", "-o", cells)
        run(pelage, "bake", cells, "--mesh", MESH, "--res", str(SIZE), "-q",
            "-o", os.path.join(tmp, "coat.exr"), "--glb", os.path.join(tmp, "coat.glb"))
        triangles = json.loads(run(pelage, "info", MESH, "--json"))["total"]["triangles"]
        # The bake's linear RGBA, as oiiotool prints it.
        texel = {}
        for line in run("oiiotool", "--dumpdata",
                        os.path.join(tmp, "coat.exr")).splitlines():
            m = re.match(r"\s*Pixel \((\d+), (\d+)\):\s+(.*)", line)
            if m:
                texel[(int(m[1]), int(m[2]))] = [float(v) for v in m[3].split()[:4]]
        check(len(texel) == SIZE * SIZE, f"oiiotool printed {len(texel)} texels")
        with open(os.path.join(tmp, "page.html"), "w") as f:
            f.write(PAGE)
        server = http.server.ThreadingHTTPServer(
            ("127.0.0.1", 0), functools.partial(Handler, directory=tmp))
        threading.Thread(target=server.serve_forever, daemon=True).start()
        try:
            with webdriver.Browser(400, 300) as b:
                b.get(f"http://127.0.0.1:{server.server_address[1]}/page.html")
                res = b.wait("return window.result", 60, "three.js to load the glTF")
        finally:
            server.shutdown()
            server.server_close()
    check("error" not in res, f"three.js could not load the glTF: {res.get('error')}")
    check(res["meshes"] == 1, f"{res['meshes']} meshes")
    check(res["indices"] == 3 * triangles, f"{res['indices']} indices for {triangles} triangles")
    check(res["normals"], "no normals")
    check(res["srgb"], "three.js does not read the base colour texture as sRGB")
    check((res["width"], res["height"]) == (SIZE, SIZE), f"texture {res['width']}x{res['height']}")
    worst, inside = 0, 0
    for x, y, r, g, b in res["samples"]:
        ref = texel[(x, y)]
        inside += ref[3] == 1
        worst = max(worst, *(abs(v - srgb_byte(ref[k])) for k, v in enumerate((r, g, b))))
    check(len(res["samples"]) == res["vertices"], "not every vertex sampled")
    check(inside == len(res["samples"]), f"{len(res['samples']) - inside} vertex UVs outside the charts")
    check(worst <= 2, f"the texture at the UVs differs from the bake by {worst}/255")
    check(res["drawn"] > 0.1 * res["pixels"], f"the frame draws {res['drawn']} pixels")
    print(f"three.js: {res['vertices']} vertices, {triangles} triangles, texture "
          f"{SIZE}x{SIZE} sRGB, worst texel {worst}/255, {res['drawn']} pixels drawn")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
