#!/usr/bin/env python3
"""Does recording off cost anything? Times this checkout's renderer against a
build of the same commit with every recorder call deleted from the tracer.

    python3 benches/without_recorder.py [--runs 15] [--scenes tetra mount ...]

The stripped copy is a `git worktree` of HEAD in a temporary directory, built
there with its own target directory (a cold build, a few minutes). Both
binaries render each SPD scene at 512 x 512 with one thread (less noisy than
two), in alternation; the table gives the whole-process time, minimum and
median, per binary and their ratio. A plain render uses `NoRecorder`, so the
question is whether its empty inlined methods leave any trace in the code.
CI does not run this.
"""

import argparse
import os
import re
import statistics
import subprocess
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SPD = os.path.join(ROOT, "scenes", "spd")
SCENES = ["balls", "gears", "mount", "rings", "teapot", "tetra", "tree"]
TRACER = os.path.join("src", "trace", "tracer.rs")


def strip_recorder_calls(source):
    """The tracer with every `rec.` call removed, and nothing else changed."""
    stripped = re.sub(r"\n\s*self\.rec\.child\(&ChildTerm \{.*?\}\);",
                      "\n        let _ = (kind, attenuation);", source, flags=re.S)
    stripped = re.sub(r"\n\s*if let Some\(refraction\) = &refraction \{\s*"
                      r"self\.rec\.refraction\(refraction\);\s*\}", "", stripped)
    stripped = re.sub(r"\n\s*(self\.)?rec\.[a-z_]+\([^;]*\);", "", stripped)
    left = re.findall(r"rec\.[a-z_]+\(", stripped)
    if left:
        raise SystemExit(f"recorder calls left after stripping: {left}")
    return stripped


def build_stripped(work):
    subprocess.run(["git", "-C", ROOT, "worktree", "add", "--detach", work, "HEAD"],
                   check=True, capture_output=True)
    path = os.path.join(work, TRACER)
    with open(path) as f:
        source = f.read()
    with open(path, "w") as f:
        f.write(strip_recorder_calls(source))
    subprocess.run(["cargo", "build", "--release", "--quiet"], cwd=work, check=True,
                   env={**os.environ, "RUSTFLAGS": "-A warnings"})
    return os.path.join(work, "target", "release", "raystep")


def seconds(binary, scene, out):
    start = time.perf_counter()
    subprocess.run([binary, "render", scene, "-o", out, "--threads", "1"],
                   check=True, capture_output=True)
    return time.perf_counter() - start


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=15)
    parser.add_argument("--scenes", nargs="+", default=SCENES)
    args = parser.parse_args()
    subprocess.run(["cargo", "build", "--release", "--quiet"], cwd=ROOT, check=True)
    with_calls = os.path.join(ROOT, "target", "release", "raystep")
    with tempfile.TemporaryDirectory() as temp:
        work = os.path.join(temp, "stripped")
        try:
            without = build_stripped(work)
            out = os.path.join(temp, "out.png")
            print(f"{args.runs} runs each, alternating, 512x512, one thread; "
                  "whole-process seconds, min / median")
            print()
            print("| scene | with recorder calls | without | ratio of minima |")
            print("|---|---:|---:|---:|")
            for name in args.scenes:
                scene = os.path.join(SPD, f"{name}.nff")
                times = {with_calls: [], without: []}
                for _ in range(args.runs + 1):
                    for binary in times:
                        times[binary].append(seconds(binary, scene, out))
                a, b = (times[with_calls][1:], times[without][1:])
                print(f"| {name} | {min(a):.3f} / {statistics.median(a):.3f} "
                      f"| {min(b):.3f} / {statistics.median(b):.3f} | {min(a) / min(b):.3f} |")
        finally:
            subprocess.run(["git", "-C", ROOT, "worktree", "remove", "--force", work],
                           capture_output=True)


if __name__ == "__main__":
    main()
