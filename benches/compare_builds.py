#!/usr/bin/env python3
"""Times two raystep binaries against each other on the SPD scenes.

    python3 benches/compare_builds.py OLD NEW [--runs 11] [--threads 1]
                                      [--size 512] [scenes ...]

OLD and NEW are paths to two builds (copy target/release/raystep aside
before changing the code); both need `render --timings`. For each scene both run `render --timings`, in
alternation (OLD, NEW, OLD, ...) after a warm-up run of each, so that both
meet the machine in the same state; the table gives each one's median and
least trace time, NEW's ratio to OLD, and the median of the runs' own
ratios (each run's two times taken moments apart). `--threads 0` uses all cores. On
this shared machine one thread is steadier than two. Differences under
about 2 % are noise; the bytes of the two renders are compared too.
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = ["balls", "gears", "mount", "rings", "teapot", "tetra", "tree"]


def trace_seconds(binary, scene, out, args):
    command = [binary, "render", scene, "-o", out, "--timings", "--size", f"{args.size}x{args.size}"]
    if args.threads > 0:
        command += ["--threads", str(args.threads)]
    result = subprocess.run(command, check=True, capture_output=True, text=True)
    return json.loads(result.stdout)["trace_seconds"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("--runs", type=int, default=11)
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("scenes", nargs="*", default=SCENES)
    args = parser.parse_intermixed_args()
    print(f"{args.size}x{args.size}, {args.threads or 'all'} thread(s), "
          f"median of {args.runs} alternating runs after a warm-up\n")
    print("| scene | old ms (median / least) | new ms (median / least) | new / old "
          "| paired new / old | same bytes |")
    print("|---|---:|---:|---:|---:|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for name in args.scenes:
            scene = os.path.join(ROOT, "scenes", "spd", f"{name}.nff")
            outs = [os.path.join(tmp, f"{which}.png") for which in ("old", "new")]
            times = ([], [])
            for run in range(args.runs + 1):
                # Which goes first alternates, so a drift of the machine's
                # speed within a pair favours neither.
                order = (0, 1) if run % 2 == 0 else (1, 0)
                for which in order:
                    binary = (args.old, args.new)[which]
                    t = trace_seconds(binary, scene, outs[which], args)
                    if run > 0:
                        times[which].append(t)
            with open(outs[0], "rb") as a, open(outs[1], "rb") as b:
                same = "yes" if a.read() == b.read() else "**no**"
            old, new = (statistics.median(t) for t in times)
            # Each run's two times were taken moments apart: the median of
            # their ratios is steadier than the ratio of the medians.
            paired = statistics.median(n / o for o, n in zip(*times))
            print(f"| {name} | {old * 1e3:.1f} / {min(times[0]) * 1e3:.1f} "
                  f"| {new * 1e3:.1f} / {min(times[1]) * 1e3:.1f} | {new / old:.3f} "
                  f"| {paired:.3f} | {same} |",
                  flush=True)


if __name__ == "__main__":
    sys.exit(main())
