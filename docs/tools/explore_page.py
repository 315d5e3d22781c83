#!/usr/bin/env python3
"""`pelage explore` on the cow with the default preset, in headless Chromium (software
WebGL), as a user drives it: its interactivity figures as JSON on stdout, and the page's
screenshots for the docs. Usage: explore_page.py PELAGE COW_MESH IMAGES_DIR > explore.json

Measured, per drag of the giraffe's repulsion radius w_r (the slider's input events):
  change_to_pattern_s  from the first input event to the first pattern of the new run
                       drawn on the canvas (the page's own clock: debounce, request,
                       simulation set-up, texture transfer and upload included)
  server_first_s       the server's share: from the run's start to its first texture
  preview_s, full_s    from the run's start to the preview's and the full scale's end
and the page's frame rate while the view turns and the server simulates (its largest gap
between frames); then the path-traced preview, and whether `pelage render` of the saved
scene gives the very same image."""
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.request

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "tests", "explore"))
import webdriver  # noqa: E402

READY = ("const s = window.pelage.status; return s && s.job >= JOB && s.result_ready && "
         "s.stats_stage === 'full' ? s : null")
# The view turning for 3 s (every frame redrawn), while the server simulates.
FRAMES = """
const done = arguments[arguments.length - 1];
const p = window.pelage;
p.controls.autoRotate = true;
p.controls.autoRotateSpeed = 20;
p.redraw();
let n = 0, t0 = performance.now(), last = t0, gap = 0;
function f() {
  const now = performance.now();
  gap = Math.max(gap, now - last); last = now; ++n;
  if (now - t0 < 3000) { requestAnimationFrame(f); return; }
  p.controls.autoRotate = false;
  done([n / ((now - t0) / 1000), gap]);
}
requestAnimationFrame(f);
"""


def drag(b, value):
    """The w_r slider moved to `value` in three input events; returns where it stopped."""
    return float(b.js(
        "const s = document.getElementById('sim-w_r-slider');"
        "const from = Number(s.value), to = arguments[0];"
        "for (const k of [1, 2, 3]) { s.value = from + (to - from) * k / 3;"
        " s.dispatchEvent(new Event('input')); }"
        "return s.value", value))


def main(pelage, mesh, images):
    out = {"mesh": os.path.basename(mesh), "preset": "giraffe-reticulata", "seed": 1,
           "browser": "headless Chromium, SwiftShader WebGL", "window": [1400, 900]}
    with tempfile.TemporaryDirectory() as saved, \
            webdriver.Explorer(pelage, [mesh, "--out", saved]) as ex, \
            webdriver.Browser(1400, 900) as b:
        b.get(ex.url)
        first = b.wait(READY.replace("JOB", "1"), 300, "the first full-scale pattern")
        out["texture_size"] = first["texture_size"]
        out["first_run"] = first["timing"]
        out["cells"] = first["texture_cells"]
        time.sleep(1)
        b.screenshot(os.path.join(images, "explore_cow.png"))
        changes = []
        for value in (6.5, 3.0, 5.5):
            job = b.js("return window.pelage.status.job")
            n = b.js("return window.pelage.timings.length")
            stopped = drag(b, value)
            # The first pattern of the new run, then the frame rate while it grows.
            b.wait(f"return window.pelage.timings.length > {n}", 60, "the first pattern")
            if value == 6.5:
                b.wait(f"const s = window.pelage.status; return s.job > {job} && "
                       "s.stage === 'full' && s.texture_stage === 'full'", 60,
                       "the full-scale run")
                fps, gap = b.js_async(FRAMES)
                out["fps_while_simulating"] = fps
                out["longest_frame_gap_s"] = gap / 1000
                b.screenshot(os.path.join(images, "explore_cow_growing.png"))
            s = b.wait(READY.replace("JOB", str(job + 1)), 300, "the full-scale pattern")
            page = b.js("return window.pelage.timings")[-1] / 1000
            changes.append({"w_r": stopped, "change_to_pattern_s": page,
                            "server_first_s": s["timing"]["first_pattern_seconds"],
                            "preview_s": s["timing"].get("preview_seconds"),
                            "full_s": s["timing"]["full_seconds"],
                            "spots": s["stats"]["spot_count"],
                            "spot_fraction_by_area": s["stats"]["spot_fraction_by_area"]})
            if value == 6.5:
                time.sleep(1)
                b.screenshot(os.path.join(images, "explore_cow_wr.png"))
        out["changes"] = changes
        out["change_to_pattern_median_s"] = statistics.median(
            c["change_to_pattern_s"] for c in changes)

        # Render and save, as the docs' last screenshot shows them; then the saved scene
        # rendered by `pelage render` at the preview's size and samples.
        t0 = time.time()
        b.js("document.getElementById('render').click()")
        b.wait("const t = document.getElementById('render-status').textContent;"
               "return t.startsWith('64 samples') && !t.endsWith('…')", 300, "the render")
        out["render_480x270_64spp_s"] = time.time() - t0
        b.js("document.getElementById('save-name').value = 'explore_cow';"
             "document.getElementById('save').click();")
        b.wait("return document.getElementById('saved').textContent.startsWith('saved')",
               60, "the save")
        b.js("document.getElementById('panel').scrollTop = 1e6")
        time.sleep(1)
        b.screenshot(os.path.join(images, "explore_cow_render.png"))
        with urllib.request.urlopen(ex.url + "api/render.png", timeout=30) as r:
            page_png = r.read()
        png = os.path.join(saved, "check.png")
        t0 = time.time()
        subprocess.run([pelage, "render", os.path.join(saved, "explore_cow.json"), "--res",
                        "480x270", "--spp", "64", "--preview", png, "-q"], check=True)
        out["saved_scene_render_s"] = time.time() - t0
        out["saved_scene_renders_the_same_image"] = open(png, "rb").read() == page_png
    json.dump(out, sys.stdout, indent=2)
    print()


if __name__ == "__main__":
    main(*sys.argv[1:4])
