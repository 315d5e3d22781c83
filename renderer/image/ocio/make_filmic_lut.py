#!/usr/bin/env python3
"""Writes filmic.spi1d, the tone curve of the config's "Filmic" view.

Input: scene-linear x after the config's lg2 allocation, i.e. t = (log2(x) + 12) / 18
(x from 2^-12 to 2^6). Output: sRGB-encoded display value of
    y = ACES filmic fit (K. Narkowicz 2015, "ACES Filmic Tone Mapping Curve",
        https://knarkowicz.wordpress.com/2016/01/06/aces-filmic-tone-mapping-curve/)
applied to 0.6 x (so scene-linear 0.18 lands near display mid-grey).
"""
import math

N = 4096
LO, HI = -12.0, 6.0

def aces(x):
    a, b, c, d, e = 2.51, 0.03, 2.43, 0.59, 0.14
    return max(0.0, min(1.0, (x * (a * x + b)) / (x * (c * x + d) + e)))

def srgb_encode(y):
    return 12.92 * y if y <= 0.0031308 else 1.055 * y ** (1 / 2.4) - 0.055

with open("filmic.spi1d", "w") as f:
    f.write("Version 1\nFrom 0.0 1.0\nLength %d\nComponents 1\n{\n" % N)
    for i in range(N):
        t = i / (N - 1)
        x = 2.0 ** (LO + t * (HI - LO))
        f.write("    %.7f\n" % srgb_encode(aces(0.6 * x)))
    f.write("}\n")
