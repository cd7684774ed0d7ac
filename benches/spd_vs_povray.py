#!/usr/bin/env python3
"""Times raystep and POV-Ray 3.7 side by side on the SPD scenes.

    python3 benches/spd_vs_povray.py [--runs 5] [--size 512] [--scenes tetra gears ...]

For each scene: `raystep render --stats` (whole-process wall time, its own
prepare and trace times, rays per second by kind, peak memory) and
../shared/bench/pov_bench.sh (wall and POV-Ray's trace time), medians of
--runs runs after one warm-up each, then POV-Ray's peak memory from one run
under /usr/bin/time. Prints Markdown tables. Without povray on the PATH the
POV-Ray columns say "skipped". CI does not run this.
"""

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.path.join(ROOT, "..", "shared")
SCENES = ["balls", "gears", "mount", "rings", "teapot", "tetra", "tree"]
RAYSTEP = os.path.join(ROOT, "target", "release", "raystep")


def raystep_runs(scene, size, runs, out):
    """Median wall, prepare and trace seconds, plus the last run's stats."""
    walls, prepares, traces, stats = [], [], [], None
    for i in range(runs + 1):
        start = time.perf_counter()
        result = subprocess.run(
            [RAYSTEP, "render", scene, "-o", out, "--stats", "--size", f"{size}x{size}"],
            check=True, capture_output=True, text=True)
        wall = time.perf_counter() - start
        stats = json.loads(result.stdout)
        if i > 0:  # the first run warms the file cache
            walls.append(wall)
            prepares.append(stats["prepare_seconds"])
            traces.append(stats["trace_seconds"])
    return statistics.median(walls), statistics.median(prepares), statistics.median(traces), stats


def povray_runs(scene, size, runs):
    """Median wall and last trace seconds from pov_bench.sh, and peak MiB."""
    if shutil.which("povray") is None:
        return None
    bench = os.path.join(SHARED, "bench", "pov_bench.sh")
    with tempfile.TemporaryDirectory() as keep:
        result = subprocess.run(
            ["bash", bench, "-n", str(runs), "-W", str(size), "-H", str(size), "-k", keep, scene],
            check=True, capture_output=True, text=True)
        values = dict(kv.split("=", 1) for line in result.stdout.splitlines()
                      for kv in line.split() if "=" in kv)
        wall = float(values["wall_median_s"])
        trace = float(values["povray_trace_s"])
        name = os.path.splitext(os.path.basename(scene))[0]
        peak = None
        if os.path.exists("/usr/bin/time"):
            timed = subprocess.run(
                ["/usr/bin/time", "-f", "%M", "povray", f"+I{name}.pov", f"+O{name}.png",
                 f"+W{size}", f"+H{size}", "-A", "+FN", "-D", "-P", "-GR", "File_Gamma=1.0"],
                cwd=keep, capture_output=True, text=True)
            peak = int(timed.stderr.strip().splitlines()[-1]) / 1024
    return wall, trace, peak


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--scenes", nargs="*", default=SCENES)
    args = parser.parse_args()
    if not os.path.exists(RAYSTEP):
        sys.exit("build first: cargo build --release")
    rows, counts = [], []
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.png")
        for name in args.scenes:
            scene = os.path.join(SHARED, "spd", f"{name}.nff")
            wall, prepare, trace, stats = raystep_runs(scene, args.size, args.runs, out)
            pov = povray_runs(scene, args.size, args.runs)
            rays = {k: stats[k] for k in ["primary", "reflected", "transmitted", "shadow"]}
            rows.append((name, wall, prepare, trace, stats.get("peak_memory_mib"), rays, pov))
            counts.append((name, stats))
            print(f"{name}: done", file=sys.stderr)

    print(f"Size {args.size}x{args.size}, depth 5, one ray per pixel centre, {os.cpu_count()} threads, "
          f"median of {args.runs} runs after a warm-up.\n")
    print("| scene | raystep wall s | prepare s | trace s | POV-Ray wall s | POV-Ray trace s "
          "| wall ratio | trace ratio | raystep MiB | POV-Ray MiB |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for name, wall, prepare, trace, peak, rays, pov in rows:
        if pov:
            pw, pt, pm = pov
            pov_cols = f"{pw:.3f} | {pt:.3f} | {wall / pw:.2f} | {trace / pt:.3f} |"
            pov_mem = f"{pm:.1f}" if pm else "?"
        else:
            pov_cols, pov_mem = "skipped | skipped | - | - |", "skipped"
        print(f"| {name} | {wall:.3f} | {prepare:.3f} | {trace:.3f} | {pov_cols} {peak or 0:.1f} | {pov_mem} |")
    print("\nRays per second while tracing (millions), by kind:\n")
    print("| scene | primary | reflected | transmitted | shadow | all |")
    print("|---|---:|---:|---:|---:|---:|")
    for name, _, _, trace, _, rays, _ in rows:
        per = {k: v / trace / 1e6 for k, v in rays.items()}
        total = sum(rays.values()) / trace / 1e6
        print(f"| {name} | {per['primary']:.2f} | {per['reflected']:.2f} | {per['transmitted']:.2f} "
              f"| {per['shadow']:.2f} | {total:.2f} |")


if __name__ == "__main__":
    main()
