#!/usr/bin/env python3
"""How much memory does loading a big scene take, TOML against NFF?

    python3 benches/scene_memory.py [--spheres 1000000] [--binary target/release/raystep]

Writes the same spheres (a 100 x 100 x N/10,000 grid, one material, one
light) as a TOML file (one three-line `[[object]]` table each) and as an NFF
file into a temporary directory, renders each at 16 x 16 under
`/usr/bin/time -v`, and prints the peak resident memory of both (the
`Maximum resident set size`, and `--timings`' own `peak_memory_mib`) and the
wall-clock time. Build with `cargo build --release` first. CI does not run this.
"""

import argparse
import json
import os
import re
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def write_scenes(directory, n):
    side = 100
    grid = [(i % side, (i // side) % side, i // (side * side)) for i in range(n)]
    toml = os.path.join(directory, "spheres.toml")
    with open(toml, "w") as f:
        f.write("[camera]\neye = [50, 50, -200]\nlook_at = [50, 50, 0]\nfov = 40\n\n")
        f.write("[materials.m]\ncolor = [1, 0.5, 0.2]\nkd = 0.7\nks = 0.3\n\n")
        f.write("[[light]]\nposition = [50, 300, -300]\n\n")
        for x, y, z in grid:
            f.write(f'[[object]]\nmaterial = "m"\nsphere = {{ center = [{x}, {y}, {z}], radius = 0.4 }}\n\n')
    nff = os.path.join(directory, "spheres.nff")
    with open(nff, "w") as f:
        f.write("v\nfrom 50 50 -200\nat 50 50 0\nup 0 1 0\nangle 40\nhither 1\nresolution 16 16\n")
        f.write("l 50 300 -300\nf 1 0.5 0.2 0.7 0.3 20 0 1\n")
        for x, y, z in grid:
            f.write(f"s {x} {y} {z} 0.4\n")
    return [nff, toml]


def measure(binary, scene, directory):
    out = os.path.join(directory, "out.png")
    command = ["/usr/bin/time", "-v", binary, "render", scene, "-o", out, "--size", "16x16", "--timings"]
    run = subprocess.run(command, capture_output=True, text=True, check=True)
    timings = json.loads(run.stdout)
    rss_kib = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", run.stderr).group(1))
    wall = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): (\S+)", run.stderr).group(1)
    return rss_kib / 1024, timings["peak_memory_mib"], wall


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--spheres", type=int, default=1_000_000)
    parser.add_argument("--binary", default=os.path.join(ROOT, "target", "release", "raystep"))
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as directory:
        for scene in write_scenes(directory, args.spheres):
            size = os.path.getsize(scene) / 1e6
            rss, peak, wall = measure(args.binary, scene, directory)
            name = os.path.basename(scene)
            print(f"{name:14} {size:6.1f} MB  max RSS {rss:7.0f} MiB  peak_memory_mib {peak:7.0f}  wall {wall}")


if __name__ == "__main__":
    main()
