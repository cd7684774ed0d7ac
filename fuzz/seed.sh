#!/bin/sh
# Fills corpus/<target>/ with the example scenes, comment lines stripped so
# that they fit in -max_len=4096. Run from fuzz/: ./seed.sh
set -e
cd "$(dirname "$0")"
mkdir -p corpus/toml_loader corpus/nff_loader corpus/trace_pixel
for f in ../scenes/*.toml; do
    name=$(basename "$f" .toml)
    grep -v '^#' "$f" > "corpus/toml_loader/$name"
    # trace_pixel: first byte even = TOML (and picks pixel (x, y) from bits 1-4).
    { printf 'J'; cat "corpus/toml_loader/$name"; } > "corpus/trace_pixel/toml-$name"
done
for f in ../scenes/spd/*-small.nff; do
    name=$(basename "$f" .nff)
    grep -v '^#' "$f" > "corpus/nff_loader/$name"
    # First byte odd = NFF.
    { printf 'K'; cat "corpus/nff_loader/$name"; } > "corpus/trace_pixel/nff-$name"
done
# student_png: small PNGs as raystep writes them (RGB, 8 bits).
mkdir -p corpus/student_png
for size in 4x3 16x12; do
    cargo run --quiet --release --manifest-path ../Cargo.toml -- \
        render ../scenes/glass.toml --size "$size" -o "corpus/student_png/glass-$size.png"
done
# raylog_reader: raystep's own logs of a few pixels of the target's scene
# (8x6, three lights, a ball and a floor), as inspect --format raylog writes them.
mkdir -p corpus/raylog_reader
sed -n '/^const SCENE: &str = r#"$/,/^"#;$/p' fuzz_targets/raylog_scene.rs | sed '1d;$d' > corpus/raylog-scene.toml
for pixel in 4,3 4,5 0,0; do
    cargo run --quiet --release --manifest-path ../Cargo.toml -- \
        inspect corpus/raylog-scene.toml --pixel "$pixel" --format raylog \
        > "corpus/raylog_reader/pixel-$pixel"
done
# A weight written as a colour, as a CSE 167 tracer logs its mirror ray's S.
sed 's/"weight": \([0-9.e-]*\)}/"weight": [\1, 0.5, 0.25]}/' corpus/raylog_reader/pixel-4,3 \
    > corpus/raylog_reader/pixel-4,3-colour-weights
# raylog_compare: the same logs, compared with the same scene.
mkdir -p corpus/raylog_compare
cp corpus/raylog_reader/* corpus/raylog_compare/
# mesh_loaders: first byte even = OBJ, odd = STL; the Cornell box (comments
# stripped) and a one-triangle ASCII STL.
mkdir -p corpus/mesh_loaders
{ printf '0'; grep -v '^#' ../scenes/cornell/cornell.obj; } > corpus/mesh_loaders/cornell-obj
printf '1solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n' \
    > corpus/mesh_loaders/triangle-stl
# test_loader: a CSE 167 .test scene using every kind of command (issue 42).
mkdir -p corpus/test_loader
printf 'size 4 3\ncamera 0 0 5 0 0 0 0 1 0 45\nambient .1 .2 .3\npushTransform\ntranslate 1 0 0\nscale 2 1 1\nsphere 0 0 0 1\npopTransform\nmaxverts 3\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\ntri 0 1 2\npoint 1 1 1 1 1 1\ndirectional 0 0 1 .5 .5 .5\nattenuation 1 0.1 0.05\n' \
    > corpus/test_loader/every-command
