#!/usr/bin/env python3
"""Measures how a coat of finite depth reflects and transmits, for a grid of coat depths N
(mean fibre cross-sections over a point of the skin) and absorptions sigma_a, and prints
the table renderer/bsdf/hair_coat_table.h holds (what sigma_a_from_coat_colour inverts).

A real coat is thin: `pelage look`'s cow has about two fibre cross-sections over each
point of skin, not the thirty of fit_hair_colour.py's thick slab, so fibres given the
thick slab's absorption let most of the light through to the skin and back, and a dark
colour comes out two to three times too bright. The coat's reflectance over a skin of
albedo s follows from two measurements by the adding equation (van de Hulst 1980;
Hanrahan & Krueger 1993 section 4 for layered surfaces):

    A(s) = R + T^2 s / (1 - s R),

with R the coat's albedo over a black skin and T^2 = (W - R)(1 - R) from W, its albedo
over a white skin (the coat's reflectance from below is taken as R). R and W are each
the coat's bihemispherical albedo, the fraction of uniform light it reflects, which is
what a Lambertian skin's albedo is: with x = cos^2 of the view's angle from the normal,
A = integral over x in [0, 1] of the albedo seen at that angle (the furnace's radiance
there, by reciprocity the albedo for light from there), by 3-point Gauss-Legendre in x
(views 19.6, 45 and 70.4 degrees above the skin, across the comb at 45 degrees of
azimuth). A thin coat seen obliquely shows more fibre and less skin, so a view along
the normal alone puts a dark coat's fibres far too light. The slab is `pelage look`'s
coat (strands tapered 4:1, combed 20 degrees from the skin with 12 degrees of jitter,
lengths +-30 %) on procedural:plane:1x1 scaled 3, in a uniform environment of radiance
1, with no path-length limit in practice, at the density that gives the depth N =
density * length * (root + tip radius) * cos(20 deg), beta_n = 0.3
(sigma_a_from_coat_colour carries other beta_n over through the thick table's ratio).
Each render measures three sigma_a at once, one per colour channel.

Usage: renderer/bsdf/fit_hair_coat.py PELAGE_BINARY [SPP] > TABLE   (about 20 minutes on
two cores at the default 48 spp); paste TABLE into hair_coat_table.h and run
clang-format on it. Python 3 standard library and oiiotool.
"""
import json
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fit_hair_colour import literal, mean_rgb  # noqa: E402  (the same slab readout)

BETA_N = 0.3
LENGTH, ROOT_RADIUS, TIP_RADIUS, COMB_DEG = 0.25, 0.002, 0.0005, 20.0
# Gauss-Legendre in x = cos^2(view from the normal) on [0, 1]: (x, weight).
VIEWS = [(0.5 - 0.5 * math.sqrt(0.6), 5 / 18), (0.5, 8 / 18), (0.5 + 0.5 * math.sqrt(0.6), 5 / 18)]
# Mean fibre cross-sections over a point of the skin (26: fit_hair_colour.py's slab).
DEPTH = [0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 26.0]
# sqrt(sigma_a), as hair_colour_table.h.
ROOT_SIGMA = [0.01, 0.02, 0.04, 0.07, 0.1, 0.15, 0.2, 0.3, 0.45, 0.65, 0.9, 1.3, 2.0]


def density_for(depth):
    return depth / (LENGTH * (ROOT_RADIUS + TIP_RADIUS) * math.cos(math.radians(COMB_DEG)))


def slab_scene(sigma_a, depth, skin, spp, out, x=1.0):
    """The slab seen at cos^2(angle from the normal) = x, across the comb (+x)."""
    mu = math.sqrt(x)
    s = math.sqrt(max(0.0, 1 - x)) / math.sqrt(2)
    eye = [3 * s, 3 * mu, 3 * s] if x < 1 else [0, 3, 0.001]
    return {
        "camera": {"position": eye, "look_at": [0, 0, 0],
                   "up": [0, 0, -1] if x >= 1 else [0, 1, 0], "fov": 8},
        "film": {"width": 24, "height": 24, "spp": spp, "output": out},
        "lights": [{"type": "environment", "colour": [1, 1, 1]}],
        "integrator": {"max_depth": 1024, "rr_depth": 1000},
        "objects": [{"name": "slab", "mesh": "procedural:plane:1x1", "transform": {"scale": 3},
                     "material": {"shader": "diffuse", "params": {"albedo": skin}},
                     "fur": {"density": density_for(depth), "length": LENGTH,
                             "length_variation": 0.3, "root_radius": ROOT_RADIUS,
                             "tip_radius": TIP_RADIUS, "segments": 6, "comb": [1, 0, 0],
                             "comb_angle": COMB_DEG, "comb_jitter": 12, "sigma_a": sigma_a,
                             "melanin_jitter": 0, "beta_n": BETA_N,
                             "max_strands": 50000000}}]}


def measure(pelage, depth, skin, spp, tmp):
    """The slab's bihemispherical albedo over a skin of albedo `skin` for every
    ROOT_SIGMA."""
    row = [0.0] * len(ROOT_SIGMA)
    for k in range(0, len(ROOT_SIGMA), 3):
        s = (ROOT_SIGMA[k:k + 3] + [ROOT_SIGMA[-1]] * 3)[:3]
        for x, weight in VIEWS:
            exr, scene = os.path.join(tmp, "slab.exr"), os.path.join(tmp, "slab.json")
            with open(scene, "w") as f:
                json.dump(slab_scene([v * v for v in s], depth, skin, spp, exr, x), f)
            subprocess.run([pelage, "render", scene, "-q"], check=True)
            a = mean_rgb(exr)
            for c in range(len(ROOT_SIGMA[k:k + 3])):
                row[k + c] += weight * a[c]
            print(f"N {depth} skin {skin} x {x:.3f} sqrt(sigma_a) {s} albedo {a}",
                  file=sys.stderr)
    return row


def main():
    pelage = sys.argv[1]
    spp = int(sys.argv[2]) if len(sys.argv) > 2 else 48
    black, transmit = [], []
    with tempfile.TemporaryDirectory() as tmp:
        for depth in DEPTH:
            r = measure(pelage, depth, 0, spp, tmp)
            w = measure(pelage, depth, 1, spp, tmp)
            black.append([-math.log(max(x, 1e-12)) for x in r])
            # T^2 = (W - R)(1 - R); never below 1e-12 (noise at the darkest entries).
            transmit.append([-math.log(max((b - a) * (1 - a), 1e-12)) for a, b in zip(r, w)])
    print(f"// Generated by renderer/bsdf/fit_hair_coat.py ({spp} spp per slab, beta_n "
          f"{BETA_N}); do not edit.")
    print("inline constexpr float hair_coat_depth[] = {" +
          ", ".join(literal(d) for d in DEPTH) + "};")
    print("// -ln R, the coat's albedo over a black skin, [depth][sqrt(sigma_a)] (the "
          "sqrt(sigma_a) of hair_colour_table.h)")
    print("inline constexpr float hair_coat_reflect[][%d] = {" % len(ROOT_SIGMA))
    for row in black:
        print("    {" + ", ".join(literal(x) for x in row) + "},")
    print("};")
    print("// -ln T^2, the coat's transmittance there and back, [depth][sqrt(sigma_a)]")
    print("inline constexpr float hair_coat_transmit[][%d] = {" % len(ROOT_SIGMA))
    for row in transmit:
        print("    {" + ", ".join(literal(x) for x in row) + "},")
    print("};")


if __name__ == "__main__":
    main()
