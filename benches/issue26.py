#!/usr/bin/env python3
"""Issue 26's measurements: trace time per SPD scene, old build against new,
memory per triangle, and two threads against one.

    python3 benches/issue26.py OLD_BINARY [NEW_BINARY] [--runs 9] [--skip-memory] [--skip-threads] [--skip-trace] [--cloud]

1. For each of the seven SPD scenes at 512 x 512 (as in scenes/spd/):
   `render --threads 1 --timings`, the old and the new binary in
   alternation (old, new, old, new, ...) after one warm-up run of each;
   the median trace_seconds of each and their ratio (old / new: above 1,
   the new is faster).
2. Memory per triangle: the SPD tetra at size factors 6, 8 and 10 (4^6,
   4^8 and 4^10 triangles, written as NFF into a temporary directory the
   as a recursive tetrahedron like the SPD's tetra program; size 6 has
   scenes/spd/tetra.nff's triangle count and file size, not its vertex
   order), rendered at 16 x 16: (peak_memory_mib - that of the same file
   with no objects) * 2^20 / triangles, each binary, the median of three
   runs. The build's prepare_seconds per triangle too.
3. The new binary at --threads 2 against --threads 1, alternating, medians:
   the speed-up of the trace.
4. With --cloud: a million spheres (the 100 x 100 x 100 grid of
   benches/scene_memory.py, as NFF) at 512 x 512, one thread, old and new in
   alternation: median trace_seconds and their ratio.

Build with `cargo build --release` first. CI does not run this.
"""

import argparse
import json
import os
import statistics
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = ["balls", "gears", "mount", "rings", "teapot", "tetra", "tree"]
HEADER = ("b 0.078 0.361 0.753\nv\nfrom 1.02285 -3.17715 -2.17451\nat -0.004103 -0.004103 0.216539\n"
          "up -0.816497 -0.816497 0.816497\nangle 45\nhither 1\nresolution 512 512\n"
          "l 2 -18 -5\nf 1 0.2 0.2 1 0 100000 0 0\n")


OUT = os.path.join(tempfile.gettempdir(), f"issue26-{os.getpid()}.png")


def timings(binary, scene, threads, size=None, out=OUT):
    command = [binary, "render", scene, "-o", out, "--threads", str(threads), "--timings"]
    if size:
        command += ["--size", size]
    run = subprocess.run(command, capture_output=True, text=True, check=True)
    return json.loads(run.stdout)


def alternate(runs, a, b):
    """Runs a() and b() in turns, after one warm-up each; both lists of results."""
    a(), b()
    first, second = [], []
    for _ in range(runs):
        first.append(a())
        second.append(b())
    return first, second


def write_tetra(path, factor):
    """The SPD tetra: a tetrahedron split into four half-size ones at its
    corners, factor - 1 times; each last one's four faces. 4^factor triangles."""
    corners = [(1, 1, 1), (-1, -1, 1), (1, -1, -1), (-1, 1, -1)]
    with open(path, "w") as f:
        f.write(HEADER)
        if factor == 0:
            return 0

        def split(centre, size, depth):
            if depth == 0:
                v = [tuple(centre[i] + size * k[i] for i in range(3)) for k in corners]
                for face in ((0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)):
                    f.write("p 3\n")
                    for i in face:
                        f.write("%.6g %.6g %.6g\n" % v[i])
                return
            half = size / 2
            for k in corners:
                split(tuple(centre[i] + half * k[i] for i in range(3)), half, depth - 1)

        split((0, 0, 0), 1.0, factor - 1)
    return 4 ** factor


def trace_table(old, new, runs):
    print(f"trace_seconds, one thread, 512 x 512, median of {runs} alternating runs")
    print(f"| scene | old s | new s | old / new |")
    print(f"|---|---:|---:|---:|")
    for name in SCENES:
        scene = os.path.join(ROOT, "scenes", "spd", name + ".nff")
        a, b = alternate(runs, lambda: timings(old, scene, 1)["trace_seconds"],
                         lambda: timings(new, scene, 1)["trace_seconds"])
        ma, mb = statistics.median(a), statistics.median(b)
        print(f"| {name} | {ma:.4f} | {mb:.4f} | {ma / mb:.3f} |", flush=True)


def memory_table(old, new):
    print("\nbytes per triangle at peak ((peak_memory_mib - empty scene's) * 2^20 / triangles), median of 3;"
          " prepare microseconds per triangle")
    print("| triangles | old bytes | new bytes | old prepare us | new prepare us |")
    print("|---:|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as directory:
        files = {}
        for factor in (0, 6, 8, 10):
            path = os.path.join(directory, f"tetra{factor}.nff")
            files[factor] = (path, write_tetra(path, factor))

        def measure(binary, factor):
            runs = [timings(binary, files[factor][0], 1, "16x16") for _ in range(3)]
            return (statistics.median(r["peak_memory_mib"] for r in runs),
                    statistics.median(r["prepare_seconds"] for r in runs))

        empty = {b: measure(b, 0)[0] for b in (old, new)}
        for factor in (6, 8, 10):
            n = files[factor][1]
            row = []
            for b in (old, new):
                peak, prepare = measure(b, factor)
                row.append(((peak - empty[b]) * 2**20 / n, prepare * 1e6 / n))
            print(f"| 4^{factor} = {n} | {row[0][0]:.0f} | {row[1][0]:.0f} | {row[0][1]:.2f} | {row[1][1]:.2f} |",
                  flush=True)


def threads_table(new, runs):
    print(f"\nthe new binary, trace_seconds at --threads 1 and 2, median of {runs} alternating runs")
    print("| scene | 1 thread s | 2 threads s | speed-up |")
    print("|---|---:|---:|---:|")
    for name in SCENES:
        scene = os.path.join(ROOT, "scenes", "spd", name + ".nff")
        a, b = alternate(runs, lambda: timings(new, scene, 1)["trace_seconds"],
                         lambda: timings(new, scene, 2)["trace_seconds"])
        ma, mb = statistics.median(a), statistics.median(b)
        print(f"| {name} | {ma:.4f} | {mb:.4f} | {ma / mb:.2f} |", flush=True)


def cloud_table(old, new, runs):
    print(f"\na million spheres (100 x 100 x 100 grid), 512 x 512, one thread, median of {runs} alternating runs")
    print("| old s | new s | old / new |")
    print("|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as directory:
        path = os.path.join(directory, "cloud.nff")
        with open(path, "w") as f:
            f.write("v\nfrom 50 50 -200\nat 50 50 0\nup 0 1 0\nangle 40\nhither 1\nresolution 512 512\n")
            f.write("l 50 300 -300\nf 1 0.5 0.2 0.7 0.3 20 0 1\n")
            for i in range(1_000_000):
                f.write(f"s {i % 100} {(i // 100) % 100} {i // 10000} 0.4\n")
        a, b = alternate(runs, lambda: timings(old, path, 1)["trace_seconds"],
                         lambda: timings(new, path, 1)["trace_seconds"])
        ma, mb = statistics.median(a), statistics.median(b)
        print(f"| {ma:.4f} | {mb:.4f} | {ma / mb:.3f} |", flush=True)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("old")
    parser.add_argument("new", nargs="?", default=os.path.join(ROOT, "target", "release", "raystep"))
    parser.add_argument("--runs", type=int, default=9)
    parser.add_argument("--skip-memory", action="store_true")
    parser.add_argument("--skip-threads", action="store_true")
    parser.add_argument("--skip-trace", action="store_true")
    parser.add_argument("--cloud", action="store_true")
    args = parser.parse_args()
    if not args.skip_trace:
        trace_table(args.old, args.new, args.runs)
    if not args.skip_memory:
        memory_table(args.old, args.new)
    if not args.skip_threads:
        threads_table(args.new, args.runs)
    if args.cloud:
        cloud_table(args.old, args.new, args.runs)


if __name__ == "__main__":
    main()
