#!/usr/bin/env python3
"""The layering, checked from the includes (CTest `style.layers`).

Data flows one way: sim -> pattern -> shader -> renderer -> apps (docs/design.md). Within
a layer, its CMakeLists.txt adds the folders in the order of the chain (add_subdirectory,
or the renderer's folder list), each using only those before it. An include of a folder that
comes later, or of a later layer, points up the chain: the linker catches it only when
the include needs a symbol, so this catches it when it is written.

Usage: check_layers.py REPO_ROOT
"""
import re
import sys
from pathlib import Path

LAYERS = ["sim", "pattern", "shader", "renderer", "apps"]
SOURCE = re.compile(r".*\.(h|hpp|c|cpp)$")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def folder_order(root, layer):
    """The layer's folders in the order its CMakeLists.txt adds them."""
    text = (root / layer / "CMakeLists.txt").read_text(encoding="utf-8")
    m = re.search(r"set\(_pelage_\w+_folders\s+([^)]*)\)", text)
    listed = m.group(1).split() if m else []
    return listed + [f for f in re.findall(r"^\s*add_subdirectory\((\w+)\)", text, re.M)
                     if f not in listed]


def main():
    root = Path(sys.argv[1]).resolve()
    rank = {}
    for li, layer in enumerate(LAYERS):
        if not (root / layer / "CMakeLists.txt").is_file():
            continue
        rank[layer] = (li, -1)  # headers at the layer's root (shader/pelage_shader.h)
        for fi, folder in enumerate(folder_order(root, layer)):
            rank[f"{layer}/{folder}"] = (li, fi)

    def rank_of(path):
        parts = Path(path).parts
        if len(parts) >= 3 and f"{parts[0]}/{parts[1]}" in rank:
            return f"{parts[0]}/{parts[1]}"
        if parts and parts[0] in rank:
            return parts[0]
        return None

    problems, checked = [], 0
    for layer in rank:
        if "/" in layer:
            continue
        for f in sorted((root / layer).rglob("*")):
            rel = f.relative_to(root).as_posix()
            if not SOURCE.match(rel) or not f.is_file():
                continue
            here = rank_of(rel)
            if here is None:
                continue
            checked += 1
            text = f.read_text(encoding="utf-8")
            for m in INCLUDE.finditer(text):
                there = rank_of(m.group(1))
                if there is None or there == here:
                    continue
                if rank[there] > rank[here]:
                    line = text.count("\n", 0, m.start()) + 1
                    problems.append(f"{rel}:{line}: includes {m.group(1)}: {there} comes "
                                    f"after {here} in the chain")
    for p in problems:
        print(p)
    print(f"check_layers: {checked} sources, {len(problems)} include(s) up the chain")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
