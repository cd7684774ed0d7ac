#!/usr/bin/env python3
"""Issue 26's primary-ray goal: each SPD scene with its lights removed and
its materials' Ks and T set to 0 (no shadow rays, no secondary rays: max
depth 1 in effect), traced by an old and a new binary in alternation.

    python3 benches/primary_only.py OLD_BINARY [NEW_BINARY] [--runs 9] [--size 512] [--write DIR]

For each of the seven SPD scenes: the scene rewritten into a temporary
directory (or DIR with --write, to profile them: `valgrind --tool=callgrind
BINARY render DIR/teapot.nff -o x.png --threads 1`), then
`render --threads 1 --timings --size SIZExSIZE`, old, new, old, new, ...
after one warm-up run of each; the median trace_seconds of each and their
ratio (old / new: above 1, the new is faster). Plain renders: no --stats,
which would take the per-ray path. CI does not run this.
"""

import argparse
import json
import os
import statistics
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = ["balls", "gears", "mount", "rings", "teapot", "tetra", "tree"]


def primary_only(text):
    """The NFF text without `l` lines, each `f` line's Ks (5th field) and T
    (7th) set to 0: NFF's f is `f r g b Kd Ks Shine T index`."""
    out = []
    for line in text.splitlines():
        words = line.split()
        if words and words[0] == "l":
            continue
        if words and words[0] == "f" and len(words) >= 9:
            words[5] = "0"
            words[7] = "0"
            line = " ".join(words)
        out.append(line)
    return "\n".join(out) + "\n"


def write_scenes(directory):
    paths = {}
    for name in SCENES:
        with open(os.path.join(ROOT, "scenes", "spd", name + ".nff")) as f:
            text = f.read()
        path = os.path.join(directory, name + ".nff")
        with open(path, "w") as f:
            f.write(primary_only(text))
        paths[name] = path
    return paths


def trace_seconds(binary, scene, size, out):
    command = [binary, "render", scene, "-o", out, "--threads", "1", "--timings",
               "--size", f"{size}x{size}"]
    run = subprocess.run(command, capture_output=True, text=True, check=True)
    return json.loads(run.stdout)["trace_seconds"]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("old")
    parser.add_argument("new", nargs="?", default=os.path.join(ROOT, "target", "release", "raystep"))
    parser.add_argument("--runs", type=int, default=9)
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--write", help="write the scenes here and stop")
    args = parser.parse_args()
    if args.write:
        os.makedirs(args.write, exist_ok=True)
        for name, path in write_scenes(args.write).items():
            print(path)
        return
    with tempfile.TemporaryDirectory() as directory:
        paths = write_scenes(directory)
        out = os.path.join(directory, "out.png")
        print("| scene | old s | new s | old / new |")
        print("|---|---:|---:|---:|")
        for name in SCENES:
            def run(binary):
                return trace_seconds(binary, paths[name], args.size, out)
            run(args.old), run(args.new)
            old, new = [], []
            for _ in range(args.runs):
                old.append(run(args.old))
                new.append(run(args.new))
            a, b = statistics.median(old), statistics.median(new)
            print(f"| {name} | {a:.4f} | {b:.4f} | {a / b:.3f} |", flush=True)


if __name__ == "__main__":
    main()
