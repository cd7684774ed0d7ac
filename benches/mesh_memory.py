#!/usr/bin/env python3
"""A million-triangle mesh: OBJ and STL against the same triangles in NFF.

    python3 benches/mesh_memory.py [--side 708] [--runs 5] [--binary target/release/raystep]

Writes a height field of side x side quads, two triangles each (708: 1,002,528
triangles), as an OBJ (`v` lines shared by neighbouring faces, `f` quads that
the loader splits), a binary STL and an NFF file of `p 3` triangles (the same
triangles, vertices written out per triangle) into a temporary directory;
renders each at 512 x 512 under `/usr/bin/time -v` and prints the peak
resident memory, `--timings`' prepare_seconds (reading the file and building
the BVH), trace_seconds and the process's CPU time (user + system, from
`time -v`: steadier than wall time on a shared machine). With `--runs N` the
three scenes run in alternation N times and each figure is a median. Build
with `cargo build --release` first. CI does not run this (the files are
about 100 MB).
"""

import argparse
import json
import math
import os
import re
import statistics
import struct
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def height(i, j, side):
    return 3.0 * math.sin(i * 12.0 / side) * math.cos(j * 9.0 / side)


def write_meshes(directory, side):
    step = 100.0 / side
    points = [[(i * step, height(i, j, side), j * step) for j in range(side + 1)] for i in range(side + 1)]
    triangles = []
    for i in range(side):
        for j in range(side):
            a, b, c, d = points[i][j], points[i + 1][j], points[i + 1][j + 1], points[i][j + 1]
            triangles.append((a, b, c))
            triangles.append((a, c, d))
    obj = os.path.join(directory, "field.obj")
    with open(obj, "w") as f:
        for row in points:
            for x, y, z in row:
                f.write(f"v {x:.5f} {y:.5f} {z:.5f}\n")
        f.write("g field\n")
        n = side + 1
        for i in range(side):
            for j in range(side):
                a = i * n + j + 1
                f.write(f"f {a} {a + n} {a + n + 1} {a + 1}\n")
    stl = os.path.join(directory, "field.stl")
    with open(stl, "wb") as f:
        f.write(b"\0" * 80 + struct.pack("<I", len(triangles)))
        for t in triangles:
            f.write(struct.pack("<12fH", 0, 0, 0, *t[0], *t[1], *t[2], 0))
    camera = "from 50 40 -60\nat 50 0 50\nup 0 1 0\nangle 45\nhither 1\nresolution 512 512\n"
    nff = os.path.join(directory, "field.nff")
    with open(nff, "w") as f:
        f.write("v\n" + camera + "l 50 100 -50\nf 0.8 0.7 0.5 1 0 0 0 1\n")
        for t in triangles:
            f.write("p 3\n")
            for x, y, z in t:
                f.write(f"{x:.5f} {y:.5f} {z:.5f}\n")
    toml = os.path.join(directory, "field.toml")
    with open(toml, "w") as f:
        f.write("[camera]\neye = [50, 40, -60]\nlook_at = [50, 0, 50]\nfov = 45\n")
        f.write("[image]\nwidth = 512\nheight = 512\n")
        f.write("[materials.m]\ncolor = [0.8, 0.7, 0.5]\n[[light]]\nposition = [50, 100, -50]\n")
        f.write('[[object]]\nmaterial = "m"\nmesh = { file = "field.obj" }\n')
    toml_stl = os.path.join(directory, "field-stl.toml")
    with open(toml_stl, "w") as f:
        f.write(open(toml).read().replace("field.obj", "field.stl"))
    return len(triangles), [nff, toml, toml_stl]


def measure(binary, scene, directory):
    out = os.path.join(directory, "out.png")
    command = ["/usr/bin/time", "-v", binary, "render", scene, "-o", out, "--size", "512x512", "--timings"]
    run = subprocess.run(command, capture_output=True, text=True, check=True)
    timings = json.loads(run.stdout)
    rss_kib = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", run.stderr).group(1))
    cpu = sum(float(re.search(rf"{kind} time \(seconds\): ([\d.]+)", run.stderr).group(1)) for kind in ("User", "System"))
    return rss_kib / 1024, timings["prepare_seconds"], timings["trace_seconds"], cpu


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--side", type=int, default=708)
    parser.add_argument("--runs", type=int, default=1)
    parser.add_argument("--binary", default=os.path.join(ROOT, "target/release/raystep"))
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as directory:
        count, scenes = write_meshes(directory, args.side)
        print(f"{count} triangles, median of {args.runs} alternating runs")
        runs = {scene: [] for scene in scenes}
        for _ in range(args.runs):
            for scene in scenes:
                runs[scene].append(measure(args.binary, scene, directory))
        print(f"{'scene':16} {'peak MiB':>9} {'load+build s':>13} {'trace s':>8} {'CPU s':>7}")
        for scene in scenes:
            rss, prepare, trace, cpu = (statistics.median(column) for column in zip(*runs[scene]))
            print(f"{os.path.basename(scene):16} {rss:9.0f} {prepare:13.2f} {trace:8.2f} {cpu:7.2f}")


if __name__ == "__main__":
    main()
