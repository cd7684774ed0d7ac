#!/bin/sh
# Builds the web page: dist/raystep.html, one self-contained file (the
# engine as WebAssembly, the page's script and every scene, compressed and
# embedded), which works from file:// and from any static host.
#
#   web/build.sh [--scenes DIR] [--out FILE]
#
# --scenes DIR  the page's built-in scenes: every .toml, .nff and .test under DIR,
#               with the meshes and MTL files beside them (default: scenes/)
# --out FILE    where the page goes (default: dist/raystep.html)
#
# Needs Debian's rustc-web toolchain (rustup's wasm32 standard library is
# not available here):
#   apt-get install -y rustc-web cargo-web rust-web-src lld
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
scenes="$root/scenes"
out="$root/dist/raystep.html"
while [ $# -gt 0 ]; do
    case "$1" in
        --scenes) scenes=${2:?--scenes needs a folder}; shift 2 ;;
        --out) out=${2:?--out needs a file}; shift 2 ;;
        -h|--help) sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) echo "web/build.sh: unknown argument $1 (try --help)" >&2; exit 2 ;;
    esac
done
for tool in /usr/bin/cargo /usr/bin/rustc wasm-ld python3; do
    if ! command -v "$tool" >/dev/null 2>&1; then
        echo "web/build.sh: $tool is missing: apt-get install -y rustc-web cargo-web rust-web-src lld python3" >&2
        exit 1
    fi
done
# The image crate needs rustc 1.88; bookworm's first rustc-web was 1.85,
# its security updates carry a newer one.
minor=$(/usr/bin/rustc --version | sed -n 's/^rustc 1\.\([0-9]*\).*/\1/p')
if [ -z "$minor" ] || [ "$minor" -lt 88 ]; then
    echo "web/build.sh: $(/usr/bin/rustc --version) is too old (the image crate needs 1.88): apt-get update && apt-get install -y rustc-web cargo-web rust-web-src" >&2
    exit 1
fi
# /usr/bin's cargo and rustc by path (rustup's come first on PATH); the
# standard library built from rust-web-src, panics abort; one codegen unit
# and full LTO, as the page runs on one thread; WebAssembly's 128-bit SIMD
# (in every browser since 2021: Chrome 91, Firefox 89, Safari 16.4), which
# makes the render about 1.3 times faster and changes no byte (the page's
# test compares every scene with the command line's); its own target
# folder, so the native build's cache is untouched.
cd "$root"
wasm_target="${CARGO_TARGET_DIR:-$root/target}/wasm"
RUSTC=/usr/bin/rustc RUSTC_BOOTSTRAP=1 \
CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_LINKER=wasm-ld \
CARGO_PROFILE_RELEASE_PANIC=abort CARGO_PROFILE_RELEASE_LTO=fat \
CARGO_PROFILE_RELEASE_CODEGEN_UNITS=1 CARGO_PROFILE_RELEASE_DEBUG=0 \
CARGO_PROFILE_RELEASE_STRIP=true RUSTFLAGS="-C target-feature=+simd128" \
    /usr/bin/cargo build --release --locked -Z build-std=std,panic_abort \
    --target wasm32-unknown-unknown -p raystep-web --target-dir "$wasm_target"
python3 "$root/web/assemble.py" \
    --wasm "$wasm_target/wasm32-unknown-unknown/release/raystep_web.wasm" \
    --scenes "$scenes" --out "$out"
