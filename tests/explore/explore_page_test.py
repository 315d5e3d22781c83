#!/usr/bin/env python3
"""`pelage explore` driven in headless Chromium (issue 37's page test): the page shows the
pattern on the mesh, the whole mesh in view; dragging the repulsion radius (w_r) re-simulates, and the new pattern
and its statistics appear; restyling the types' colours repaints without simulating, and
the canvas then shows both colours; Save writes a preset that `pelage sim` grows into
the same bytes, and a scene that `pelage render` renders from those cells without growing
them again, to the very image of the page's path-traced preview. Everything is started and stopped here,
each wait bounded. Usage: explore_page_test.py PELAGE. Exit 77 (skipped) when Chromium or
its driver is missing."""
import json
import os
import subprocess
import sys
import tempfile
import urllib.request

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import webdriver  # noqa: E402

MESH = "procedural:sphere:20x20"

# The canvas's pixels whose colour is clearly red, and clearly blue, and all of them.
COUNT_COLOURS = """
const c = document.getElementById('canvas');
const o = document.createElement('canvas');
o.width = c.width; o.height = c.height;
const g = o.getContext('2d');
g.drawImage(c, 0, 0);
const d = g.getImageData(0, 0, o.width, o.height).data;
let red = 0, blue = 0;
for (let i = 0; i < d.length; i += 4) {
  const r = d[i], gr = d[i + 1], b = d[i + 2];
  if (r > 60 && gr < 0.2 * r && b < 0.2 * r) ++red;
  if (b > 60 && r < 0.2 * b && gr < 0.2 * b) ++blue;
}
return [red, blue, d.length / 4];
"""

# The largest |NDC| coordinate of the mesh's vertices in the page's camera (1: the canvas
# border).
FARTHEST_VERTEX = """
const p = window.pelage, cam = p.controls.object;
cam.updateMatrixWorld();
const pos = p.mesh.geometry.attributes.position, v = cam.position.clone();
let most = 0;
for (let i = 0; i < pos.count; ++i) {
  v.fromBufferAttribute(pos, i).project(cam);
  most = Math.max(most, Math.abs(v.x), Math.abs(v.y));
}
return most;
"""


def check(condition, message):
    if not condition:
        raise AssertionError(message)


def main(pelage):
    if not webdriver.browser_available():
        print("skipped: chromium or chromium-driver is not installed")
        return 77
    with tempfile.TemporaryDirectory() as tmp, \
            webdriver.Explorer(pelage, [MESH, "--preset", "teo-leopard", "--out", tmp]) as ex, \
            webdriver.Browser() as b:
        b.get(ex.url)
        first = b.wait("const s = window.pelage.status; return s && s.result_ready && "
                       "window.pelage.textureVersion > 0 ? s : null", 90, "the first pattern")
        job0, stats0 = first["job"], first["stats"]
        # The view starts with the whole mesh in it, framed as `pelage look` frames it:
        # through the camera three.js draws with, every vertex projects inside the canvas
        # less an 8 % margin, and one on that border.
        most = b.js(FARTHEST_VERTEX)
        print(f"start view: farthest vertex at {most:.3f} of the half-canvas")
        check(0.85 < most < 0.93,
              f"the start view puts its farthest vertex at {most:.3f} of the half-canvas")
        w_r = first["preset"]["simulation"]["w_r"]

        # Drag the repulsion radius: the slider's input events, as a mouse sends them.
        dragged = float(b.js(
            "const s = document.getElementById('sim-w_r-slider');"
            "for (const v of arguments[0]) { s.value = v; s.dispatchEvent(new Event('input')); }"
            "return s.value", [w_r * 1.2, w_r * 1.4, w_r * 1.6]))
        after = b.wait("const s = window.pelage.status; return s && s.job > arguments[0] && "
                       "s.result_ready && s.stats_stage === 'full' && "
                       "window.pelage.timings.length > 0 ? s : null".replace(
                           "arguments[0]", str(job0)), 120, "the new pattern")
        check(abs(dragged - w_r * 1.6) < 0.01 * w_r, f"the slider stopped at {dragged}")
        check(after["preset"]["simulation"]["w_r"] == dragged,
              f"the server grew w_r {after['preset']['simulation']['w_r']}, not {dragged}")
        check(after["stats"] != stats0, "the statistics did not change with w_r")
        shown = b.js("return document.getElementById('stat-spots').textContent")
        check(shown == str(after["stats"]["spot_count"]),
              f"the panel shows {shown} spots, the server measured {after['stats']['spot_count']}")
        timings = b.js("return window.pelage.timings")
        print(f"change to first pattern shown: {timings[-1] / 1000:.2f} s")

        # Restyle F red and B blue: no new simulation, and the canvas shows both.
        b.js("for (const [id, v] of arguments[0]) { const c = document.getElementById(id);"
             " c.value = v; c.dispatchEvent(new Event('input')); }",
             [["type-0-colour", "#ff0000"], ["type-1-colour", "#0000ff"]])
        restyled = b.wait("const s = window.pelage.status; return s && "
                          "s.types[0].colour[0] === 1 && s.types[1].colour[2] === 1 ? s : null",
                          20, "the new colours")
        check(restyled["job"] == after["job"], "a colour change simulated again")
        red, blue, total = b.wait("const n = (function(){" + COUNT_COLOURS + "})();"
                                  "return n[0] > 0 && n[1] > 0 ? n : null", 20,
                                  "red and blue pixels")
        print(f"canvas: {red} red and {blue} blue pixels of {total}")
        check(red > 0.002 * total and blue > 0.002 * total,
              f"too few pixels of the type colours: {red} red, {blue} blue of {total}")
        b.screenshot(os.path.join(tmp, "page.png"))

        # Save, then grow the saved preset with `pelage sim`: the same bytes.
        b.js("document.getElementById('save-name').value = 'leo';"
             "document.getElementById('save').click();")
        b.wait("return document.getElementById('saved').textContent.startsWith('saved')", 30,
               "the save")
        preset, cells, scene = (os.path.join(tmp, f) for f in
                                ("leo_preset.json", "leo.cells", "leo.json"))
        for f in (preset, cells, scene):
            check(os.path.exists(f), f"save did not write {f}")
        saved = json.load(open(preset))
        check(saved["types"][0]["colour"] == [1, 0, 0], "the saved preset lost the new colour")
        grown = os.path.join(tmp, "sim.cells")
        subprocess.run([pelage, "sim", "--mesh", MESH, "--preset", preset, "--seed",
                        str(after["seed"]), "-o", grown, "-q"], check=True, timeout=120)
        check(open(grown, "rb").read() == open(cells, "rb").read(),
              "pelage sim grew other cells from the saved preset")

        # The path-traced preview, progressively to its last pass.
        b.js("document.getElementById('render').click()")
        status = b.wait("const t = document.getElementById('render-status').textContent;"
                        "return (t.startsWith('64 samples') && !t.endsWith('…')) || "
                        "(t && !t.includes('samples')) ? t : null", 120, "the preview render")
        check(status.startswith("64 samples"), f"the preview render failed: {status}")
        check(b.js("const i = document.getElementById('render-image');"
                   "return i.complete && i.naturalWidth") == 480, "no preview image shown")

        with urllib.request.urlopen(ex.url + "api/render.png", timeout=30) as r:
            page_png = r.read()

        # The saved scene renders from the saved cells (they are not grown again) to the
        # very image the page showed, at its size and samples.
        before = open(cells, "rb").read()
        check_png = os.path.join(tmp, "check.png")
        r = subprocess.run([pelage, "render", scene, "--res", "480x270", "--spp", "64",
                            "--preview", check_png], capture_output=True, text=True,
                           timeout=300)
        check(r.returncode == 0, f"pelage render failed: {r.stderr}")
        check("growing" not in r.stderr, f"pelage render grew the pattern again: {r.stderr}")
        check(open(cells, "rb").read() == before, "pelage render rewrote the cells")
        check(open(check_png, "rb").read() == page_png,
              "pelage render of the saved scene differs from the page's preview")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
