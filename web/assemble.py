#!/usr/bin/env python3
"""Puts the web page together: page.html with its style, its scripts, the
engine's .wasm and the built-in scenes inlined, so that the one file works
from file:// with no network. The module and the scenes are gzipped and
base64-encoded; the page unpacks them with the browser's
DecompressionStream.

    python3 web/assemble.py --wasm FILE.wasm --scenes DIR --out FILE.html
"""

import argparse
import base64
import gzip
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
# What a scene folder's files may be: scenes, and the meshes and MTL files
# they name. Anything else (a README) stays out of the page.
SCENE_FILES = (".toml", ".nff", ".test")
MESH_FILES = (".obj", ".mtl", ".stl")


def packed(data: bytes) -> str:
    """gzip, then base64: what the page's `unpack` reads. mtime=0 keeps the
    bytes the same from one build to the next."""
    return base64.b64encode(gzip.compress(data, 9, mtime=0)).decode("ascii")


def is_assignment(path: str) -> bool:
    """A grading assignment (docs/TEACHERS.md) lists [[scene]] tables; it
    is not a scene to open."""
    if not path.lower().endswith(".toml"):
        return False
    with open(path, "rb") as f:
        return any(line.strip() == b"[[scene]]" for line in f)


def scene_bundle(folder: str) -> bytes:
    """Every scene and mesh file under `folder`, as one archive: a JSON
    header line (each file's path, relative to `folder`, and length), then
    the files' bytes one after another, in path order."""
    files = []
    for top, dirs, names in os.walk(folder):
        dirs.sort()
        for name in sorted(names):
            path = os.path.join(top, name)
            if name.lower().endswith(SCENE_FILES + MESH_FILES) and not is_assignment(path):
                files.append((os.path.relpath(path, folder).replace(os.sep, "/"), path))
    if not any(p.lower().endswith(SCENE_FILES) for p, _ in files):
        sys.exit(f"assemble.py: {folder} holds no .toml or .nff scene")
    blobs = []
    for rel, path in files:
        with open(path, "rb") as f:
            blobs.append(f.read())
    header = json.dumps([[rel, len(b)] for (rel, _), b in zip(files, blobs)])
    return header.encode("utf-8") + b"\n" + b"".join(blobs)


def read(name: str) -> str:
    with open(os.path.join(HERE, name), encoding="utf-8") as f:
        return f.read()


def script_text(text: str) -> str:
    """Text safe inside a <script> element."""
    return text.replace("</script", "<\\/script")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--wasm", required=True)
    parser.add_argument("--scenes", required=True)
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    if not os.path.isdir(args.scenes):
        sys.exit(f"assemble.py: --scenes {args.scenes} is not a folder")
    with open(args.wasm, "rb") as f:
        wasm = f.read()
    common = read("common.js")
    page = read("page.html")
    for marker, text in [
        ("/*STYLE*/", read("page.css")),
        ("/*WASM*/", packed(wasm)),
        ("/*SCENES*/", packed(scene_bundle(args.scenes))),
        ("/*WORKER*/", script_text(json.dumps(common + read("worker.js")))),
        ("/*SCRIPT*/", script_text(common + read("page.js"))),
    ]:
        if page.count(marker) != 1:
            sys.exit(f"assemble.py: page.html must hold {marker} once")
        page = page.replace(marker, text)
    out_dir = os.path.dirname(os.path.abspath(args.out))
    os.makedirs(out_dir, exist_ok=True)
    # Written beside, then renamed: a page open in a browser is never half written.
    temp = args.out + ".part"
    with open(temp, "w", encoding="utf-8") as f:
        f.write(page)
    os.replace(temp, args.out)
    size = os.path.getsize(args.out)
    print(f"{args.out}: {size / 1e6:.2f} MB (engine {len(wasm) / 1e6:.2f} MB before gzip)")


if __name__ == "__main__":
    main()
