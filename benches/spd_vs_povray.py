#!/usr/bin/env python3
"""Times raystep and POV-Ray 3.7 side by side on the SPD scenes.

    python3 benches/spd_vs_povray.py [--runs 5] [--size 512] [--scenes tetra gears ...]

For each scene: `raystep render --timings` (whole-process wall time, its own
prepare and trace times of a plain render, which counts nothing, and peak
memory; one more run with `--stats` gives the ray counts for the rays per
second by kind) and
benches/pov/pov_bench.sh -n 1 (wall and POV-Ray's trace time of one
render), run in alternation, --runs times each after one warm-up each; the
tables give medians. Alternating lets both programs meet the same state of a
shared, noisy machine, and makes POV-Ray's trace time a median too (one
pov_bench.sh call with -n N reports the trace time of its last run only).
Then POV-Ray's peak memory from one run under /usr/bin/time. Prints Markdown
tables. Without povray on the PATH the POV-Ray columns say "skipped". CI
does not run this.
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
SPD = os.path.join(ROOT, "scenes", "spd")
SCENES = ["balls", "gears", "mount", "rings", "teapot", "tetra", "tree"]
RAYSTEP = os.path.join(ROOT, "target", "release", "raystep")


def raystep_run(scene, size, out, report="--timings"):
    """Wall, prepare and trace seconds of one run, and what it reported:
    timings and peak memory (`--timings`), or ray counts too (`--stats`,
    tracing with counters, a little slower)."""
    start = time.perf_counter()
    result = subprocess.run(
        [RAYSTEP, "render", scene, "-o", out, report, "--size", f"{size}x{size}"],
        check=True, capture_output=True, text=True)
    wall = time.perf_counter() - start
    stats = json.loads(result.stdout)
    return wall, stats["prepare_seconds"], stats["trace_seconds"], stats


def povray_run(scene, size, keep=None):
    """Wall and trace seconds of one pov_bench.sh run (one render, timed)."""
    bench = os.path.join(ROOT, "benches", "pov", "pov_bench.sh")
    command = ["bash", bench, "-n", "1", "-W", str(size), "-H", str(size)]
    if keep:
        command += ["-k", keep]
    result = subprocess.run(command + [scene], check=True, capture_output=True, text=True)
    values = dict(kv.split("=", 1) for line in result.stdout.splitlines()
                  for kv in line.split() if "=" in kv)
    return float(values["wall_median_s"]), float(values["povray_trace_s"])


def povray_peak_mib(keep, name, size):
    """POV-Ray's peak memory in one more render, or None without /usr/bin/time."""
    if not os.path.exists("/usr/bin/time"):
        return None
    timed = subprocess.run(
        ["/usr/bin/time", "-f", "%M", "povray", f"+I{name}.pov", f"+O{name}.png",
         f"+W{size}", f"+H{size}", "-A", "+FN", "-D", "-P", "-GR", "File_Gamma=1.0"],
        cwd=keep, capture_output=True, text=True)
    return int(timed.stderr.strip().splitlines()[-1]) / 1024


def measure(scene, size, runs, out):
    """Medians of `runs` runs of each program, taken in alternation (raystep,
    POV-Ray, raystep, ...) after one warm-up run of each, so that both see
    the machine in the same state; the trace ratio is the ratio of the two
    trace medians."""
    with_pov = shutil.which("povray") is not None
    name = os.path.splitext(os.path.basename(scene))[0]
    ours, theirs, stats, peak = [], [], None, None
    with tempfile.TemporaryDirectory() as keep:
        for i in range(runs + 1):
            *run, stats = raystep_run(scene, size, out)
            pov = povray_run(scene, size, keep if i == 0 else None) if with_pov else None
            if i > 0:  # the first runs warm the file cache
                ours.append(run)
                theirs.append(pov)
        if with_pov:
            peak = povray_peak_mib(keep, name, size)
    counted = raystep_run(scene, size, out, "--stats")[-1]
    stats = {**counted, "peak_memory_mib": stats.get("peak_memory_mib")}
    wall, prepare, trace = (statistics.median(column) for column in zip(*ours))
    pov = None
    if with_pov:
        pov_wall, pov_trace = (statistics.median(column) for column in zip(*theirs))
        pov = (pov_wall, pov_trace, peak)
    return wall, prepare, trace, stats, pov


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
            scene = os.path.join(SPD, f"{name}.nff")
            wall, prepare, trace, stats, pov = measure(scene, args.size, args.runs, out)
            rays = {k: stats[k] for k in ["primary", "reflected", "transmitted", "shadow"]}
            rows.append((name, wall, prepare, trace, stats.get("peak_memory_mib"), rays, pov))
            counts.append((name, stats))
            print(f"{name}: done", file=sys.stderr)

    print(f"Size {args.size}x{args.size}, depth 5, one ray per pixel centre, {os.cpu_count()} threads, "
          f"median of {args.runs} runs of each program after a warm-up, raystep and POV-Ray "
          f"in alternation.\n")
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
