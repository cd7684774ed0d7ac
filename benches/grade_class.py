#!/usr/bin/env python3
"""How long does `raystep grade` take on a class?

    python3 benches/grade_class.py [--students 100] [--runs 5] [--jobs N] [--keep DIR]

Makes a class of made-up students for scenes/assignment.toml (five scenes
at 160 x 120): raystep renders each scene once correctly and once under
each of a dozen classic mistakes and a few pairs of them (`raystep render
--mistake ...`), and each student's folder gets copies of those images, a
third of them correct, the rest mistaken, spread so that every mistake is
made by several students. Then it times `raystep grade` on the class
(whole-process wall time, after a warm-up run) and prints each run and the
median. Build with `cargo build --release` first. CI does not run this.
`--keep DIR` writes the class to DIR (DIR/submissions, DIR/report) and
keeps it, to look at the report.
"""

import argparse
import os
import shutil
import statistics
import subprocess
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ASSIGNMENT = os.path.join(ROOT, "scenes", "assignment.toml")
SCENES = ["shadows", "highlights", "mirrors", "glass", "attenuation"]
# What a handed-in image was rendered with: nothing (correct), one mistake
# or two. Correct images come up twice as often as in the list.
KINDS = [
    [], [], [],
    ["no-ambient"], ["flipped-y"], ["gamma"], ["phong-not-blinn"],
    ["shadow-acne"], ["opaque-shadows"], ["byte-wrap"], ["no-normal-flip"],
    ["reflection-sign"], ["eta-inverted"], ["depth-off-by-one"],
    ["light-not-normalised"],
    ["no-ambient", "phong-not-blinn"], ["gamma", "flipped-y"],
    ["shadow-acne", "reflection-sign"],
]


def render_all(binary, directory):
    """Each scene under each kind: {(scene, kind index): png path}."""
    renders = {}
    for scene in SCENES:
        for k, mistakes in enumerate(KINDS):
            if k > 0 and not mistakes:
                renders[(scene, k)] = renders[(scene, 0)]
                continue
            out = os.path.join(directory, f"{scene}-{k}.png")
            command = [binary, "render", os.path.join(ROOT, "scenes", f"{scene}.toml"), "-o", out]
            for m in mistakes:
                command += ["--mistake", m]
            subprocess.run(command, check=True)
            renders[(scene, k)] = out
    return renders


def make_class(renders, submissions, students):
    os.makedirs(submissions)
    for i in range(students):
        folder = os.path.join(submissions, f"student {i:03d}")
        os.makedirs(folder)
        for j, scene in enumerate(SCENES):
            kind = (i * 7 + j * 3) % len(KINDS)
            shutil.copy(renders[(scene, kind)], os.path.join(folder, f"{scene}.png"))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--students", type=int, default=100)
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--jobs", type=int)
    parser.add_argument("--keep", help="write the class here and keep it")
    parser.add_argument("--binary", default=os.path.join(ROOT, "target", "release", "raystep"))
    args = parser.parse_args()
    work = args.keep or tempfile.mkdtemp()
    try:
        renders_dir = os.path.join(work, "renders")
        os.makedirs(renders_dir, exist_ok=True)
        submissions = os.path.join(work, "submissions")
        shutil.rmtree(submissions, ignore_errors=True)
        make_class(render_all(args.binary, renders_dir), submissions, args.students)
        report = os.path.join(work, "report")
        command = [args.binary, "grade", ASSIGNMENT, submissions, "-o", report]
        if args.jobs:
            command += ["--jobs", str(args.jobs)]
        print(" ".join(command))
        subprocess.run(command, check=True, capture_output=True)  # warm-up
        seconds = []
        for run in range(args.runs):
            started = time.perf_counter()
            done = subprocess.run(command, check=True, capture_output=True, text=True)
            seconds.append(time.perf_counter() - started)
            print(f"run {run + 1}: {seconds[-1]:.2f} s  {done.stdout.strip()}")
        print(f"{args.students} students x {len(SCENES)} scenes at 160x120: "
              f"median {statistics.median(seconds):.2f} s over {args.runs} runs")
    finally:
        if not args.keep:
            shutil.rmtree(work)


if __name__ == "__main__":
    main()
