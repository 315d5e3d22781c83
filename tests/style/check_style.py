#!/usr/bin/env python3
"""The repository's mechanical rules, run by CTest (test `style.source`):

1. every C/C++ source is clang-format clean against the repository's .clang-format;
2. no line is longer than 90 columns (counted in characters), except inside raw string
   literals (test scenes written as JSON keep their natural shape); CMake files too,
   with no tab and no trailing space (nothing formats them: C++'s formatter mangles
   them);
3. no file refers to material outside the repository.

Usage: check_style.py REPO_ROOT [CLANG_FORMAT]
"""
import re
import subprocess
import sys
from pathlib import Path

COLUMNS = 90
SOURCE = re.compile(r".*\.(h|hpp|c|cpp)$")
CMAKE = re.compile(r"(^|.*/)(CMakeLists\.txt|[^/]*\.cmake)$")
# Anything under these never passes through the rules: fuzz inputs are arbitrary bytes.
SKIP = ("tests/fuzz/corpus/", "tests/fuzz/crashes/")
OUTSIDE = re.compile(r"\.\./shared|shared/(seeds|research)|style\.md")


def tracked_files(root):
    git = subprocess.run(["git", "-C", str(root), "ls-files"], capture_output=True, text=True)
    if git.returncode == 0:
        out = git.stdout.split()
    else:  # an unpacked archive: every file but build trees
        out = [str(p.relative_to(root)) for p in root.rglob("*")
               if p.is_file() and not p.relative_to(root).parts[0].startswith((".", "build"))]
    return [f for f in out if not f.startswith(SKIP)]


def long_lines(path):
    """Lines over COLUMNS outside raw string literals R"(...)" and R"delim(...)delim"."""
    bad = []
    closing = None
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        rest = line
        inside = closing is not None
        while True:
            if closing is not None:
                end = rest.find(closing)
                if end < 0:
                    break
                rest, closing = rest[end + len(closing):], None
            m = re.search(r'R"([^()\\ ]{0,16})\(', rest)
            if not m:
                break
            inside = True
            closing = ")" + m.group(1) + '"'
            rest = rest[m.end():]
        if len(line) > COLUMNS and not inside:
            bad.append(f"{path}:{number}: {len(line)} columns (limit {COLUMNS})")
    return bad


def main():
    root = Path(sys.argv[1]).resolve()
    clang_format = sys.argv[2] if len(sys.argv) > 2 else "clang-format"
    files = tracked_files(root)
    sources = [root / f for f in files if SOURCE.match(f)]
    problems = []

    fmt = subprocess.run([clang_format, "--dry-run", "--Werror",
                          f"--style=file:{root / '.clang-format'}"] + [str(s) for s in sources],
                         capture_output=True, text=True)
    if fmt.returncode != 0:
        unformatted = sorted(set(re.findall(r"^(\S+?):\d+:\d+: error", fmt.stderr, re.M)))
        problems += [f"{f}: not clang-format clean (run: clang-format -i {f})"
                     for f in unformatted] or [fmt.stderr.strip()]

    for s in sources:
        problems += long_lines(s)
    for f in files:
        if not CMAKE.match(f) or not (root / f).is_file():
            continue
        for number, line in enumerate((root / f).read_text(encoding="utf-8").splitlines(), 1):
            if len(line) > COLUMNS:
                problems.append(f"{f}:{number}: {len(line)} columns (limit {COLUMNS})")
            if "\t" in line or line != line.rstrip():
                problems.append(f"{f}:{number}: a tab or a trailing space")

    for f in files:
        p = root / f
        if p.suffix in (".png", ".exr", ".spi1d") or not p.is_file():
            continue
        try:
            text = p.read_text(encoding="utf-8")
        except UnicodeDecodeError:
            continue
        for number, line in enumerate(text.splitlines(), 1):
            if OUTSIDE.search(line) and f != "tests/style/check_style.py":
                problems.append(f"{f}:{number}: refers to files outside the repository")

    for p in problems:
        print(p)
    print(f"check_style: {len(sources)} sources, {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
