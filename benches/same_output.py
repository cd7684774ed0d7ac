#!/usr/bin/env python3
"""Do two builds render the same images and ray counts?

    python3 benches/same_output.py OLD_BINARY [NEW_BINARY] [--all-counts]

Renders every scene under scenes/ (TOML and NFF, the SPD scenes included)
with both binaries at --threads 1 and 2, with `--stats`, and compares the
PNGs byte for byte and the ray counts of `--stats` (primary, reflected,
transmitted, shadow and their hits, blocked, opaque, not cast). Node and
primitive test counts may differ between builds (another tree); with
`--all-counts` they must be equal too.

With `--plain`, renders without `--stats` instead (the path of plain
renders: a row's primary rays in packets, no counts) and compares the
PNGs alone, of every scene at 1 and 2 threads and of every classic
mistake on each TOML scene at the top of scenes/. Exits 1 on any
difference.
"""

import argparse
import filecmp
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RAYS = ["primary", "primary_hit", "reflected", "transmitted", "shadow",
        "shadow_blocked", "shadow_opaque", "not_cast", "objects", "lights"]
COSTS = ["closest_nodes", "closest_primitives", "shadow_nodes", "shadow_primitives"]


def scenes():
    found = []
    for directory, _, files in os.walk(os.path.join(ROOT, "scenes")):
        for name in files:
            if name.endswith((".toml", ".nff")) and "assignments" not in directory:
                found.append(os.path.join(directory, name))
    return sorted(found)


def render(binary, scene, threads, out):
    run = subprocess.run([binary, "render", scene, "-o", out, "--threads", str(threads), "--stats"],
                         capture_output=True, text=True, check=True)
    return json.loads(run.stdout)


def mistakes(binary):
    """The --mistake names the binary's help lists."""
    run = subprocess.run([binary, "render", "--help"], capture_output=True, text=True, check=True)
    listed = run.stdout.split("possible values: ", 1)[1].split("]", 1)[0]
    return [name.strip() for name in listed.split(",")]


def plain(old, new):
    """Plain renders (no --stats) compared byte for byte; the number that differ."""
    differ = compared = 0
    with tempfile.TemporaryDirectory() as directory:
        a, b = os.path.join(directory, "old.png"), os.path.join(directory, "new.png")
        runs = [(scene, ["--threads", str(t)]) for scene in scenes() for t in (1, 2)]
        top = sorted(os.path.join(ROOT, "scenes", n) for n in os.listdir(os.path.join(ROOT, "scenes"))
                     if n.endswith(".toml"))
        runs += [(scene, ["--mistake", m]) for scene in top for m in mistakes(old)]
        for scene, extra in runs:
            done = [subprocess.run([binary, "render", scene, "-o", out] + extra,
                                   capture_output=True).returncode
                    for binary, out in ((old, a), (new, b))]
            if done[0] != 0 and done[1] != 0:
                continue  # a mistake the scene cannot show: both refuse it
            same = done == [0, 0] and filecmp.cmp(a, b, shallow=False)
            compared += 1
            differ += not same
            if not same:
                print(f"DIFFERENT {os.path.relpath(scene, ROOT)} {' '.join(extra)}")
        print(f"{compared} plain renders compared, {differ} difference(s)")
    return differ


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("old")
    parser.add_argument("new", nargs="?", default=os.path.join(ROOT, "target/release/raystep"))
    parser.add_argument("--all-counts", action="store_true")
    parser.add_argument("--plain", action="store_true")
    args = parser.parse_args()
    if args.plain:
        sys.exit(1 if plain(args.old, args.new) else 0)
    keys = RAYS + (COSTS if args.all_counts else [])
    differ = 0
    with tempfile.TemporaryDirectory() as directory:
        for scene in scenes():
            for threads in (1, 2):
                a, b = os.path.join(directory, "old.png"), os.path.join(directory, "new.png")
                old, new = render(args.old, scene, threads, a), render(args.new, scene, threads, b)
                bad = [k for k in keys if old.get(k) != new.get(k)]
                same_png = filecmp.cmp(a, b, shallow=False)
                costs = "same costs" if all(old[k] == new[k] for k in COSTS) else "costs differ"
                status = "same" if same_png and not bad else "DIFFERENT"
                differ += status != "same"
                print(f"{status:9} {os.path.relpath(scene, ROOT):32} threads {threads}  "
                      f"png {'=' if same_png else '!='}  {costs}  {' '.join(bad)}")
    print(f"{differ} difference(s)")
    sys.exit(1 if differ else 0)


if __name__ == "__main__":
    main()
