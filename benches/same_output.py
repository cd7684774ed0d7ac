#!/usr/bin/env python3
"""Do two builds render the same images and ray counts?

    python3 benches/same_output.py OLD_BINARY [NEW_BINARY] [--all-counts]

Renders every scene under scenes/ (TOML and NFF, the SPD scenes included)
with both binaries at --threads 1 and 2, with `--stats`, and compares the
PNGs byte for byte and the ray counts of `--stats` (primary, reflected,
transmitted, shadow and their hits, blocked, opaque, not cast). Node and
primitive test counts may differ between builds (another tree); with
`--all-counts` they must be equal too. Exits 1 on any difference.
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


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("old")
    parser.add_argument("new", nargs="?", default=os.path.join(ROOT, "target/release/raystep"))
    parser.add_argument("--all-counts", action="store_true")
    args = parser.parse_args()
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
