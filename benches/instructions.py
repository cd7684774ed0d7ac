#!/usr/bin/env python3
"""Instructions of the trace alone, two raystep binaries on the SPD scenes:
the one measure on this shared machine that does not move from run to run.

    python3 benches/instructions.py OLD [NEW] [--size 256] [--primary-only] [scenes ...]

For each scene and binary, `valgrind --tool=callgrind` counts the whole
process at SIZE x SIZE and at 1 x 1 (parse, build and start-up, no trace to
speak of), one thread; the difference is the trace's. With --primary-only
the scenes are first rewritten as benches/primary_only.py does (no lights,
Ks and T 0). The table gives millions of instructions and OLD / NEW (above
1, the new one runs fewer). Needs valgrind; CI does not run this.
"""

import argparse
import os
import re
import subprocess
import tempfile

import primary_only

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = ["balls", "gears", "mount", "rings", "teapot", "tetra", "tree"]


def instructions(binary, scene, size):
    """The instructions callgrind counts for one render."""
    with tempfile.TemporaryDirectory() as directory:
        command = [
            "valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null",
            binary, "render", scene, "-o", os.path.join(directory, "x.png"),
            "--size", f"{size}x{size}", "--threads", "1",
        ]
        done = subprocess.run(command, capture_output=True, text=True, check=True)
    counts = re.findall(r"Collected : (\d+)", done.stderr)
    if not counts:
        raise SystemExit(f"no instruction count from callgrind for {scene}:\n{done.stderr}")
    return int(counts[-1])


def trace_instructions(binary, scene, size):
    return instructions(binary, scene, size) - instructions(binary, scene, 1)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("old")
    parser.add_argument("new", nargs="?", default=os.path.join(ROOT, "target", "release", "raystep"))
    parser.add_argument("--size", type=int, default=256)
    parser.add_argument("--primary-only", action="store_true")
    parser.add_argument("scenes", nargs="*", default=SCENES)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as directory:
        if args.primary_only:
            primary_only.write_scenes(directory)
            path = lambda name: os.path.join(directory, f"{name}.nff")
        else:
            path = lambda name: os.path.join(ROOT, "scenes", "spd", f"{name}.nff")
        kind = "primary rays only" if args.primary_only else "whole scene"
        print(f"trace instructions (millions), {kind}, {args.size} x {args.size}, one thread")
        print("| scene | old | new | old / new |")
        print("|---|---:|---:|---:|")
        for name in args.scenes:
            old = trace_instructions(args.old, path(name), args.size)
            new = trace_instructions(args.new, path(name), args.size)
            print(f"| {name} | {old / 1e6:.2f} | {new / 1e6:.2f} | {old / new:.3f} |", flush=True)


if __name__ == "__main__":
    main()
