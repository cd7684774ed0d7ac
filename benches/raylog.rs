//! Reading a million-line ray log (issue 21: "a log of a million lines
//! compares in bounded memory (at most 64 MiB beyond the scene's) and in
//! under 2 s on 2 cores"). Run with `cargo bench --bench raylog`.
//!
//! Writes raystep's own log of scenes/spd/balls.nff at 512x512 (`raylog`
//! of each pixel's recorded tree, pixels in image order) until it holds a
//! million lines, into a temporary file; times reading it whole with
//! `RaylogReader` (a warm-up, then the median of `RUNS`: one read takes
//! seconds, so criterion's ten samples and warm-up would hold the shared
//! machine for a minute); then this binary runs itself once more to read the
//! log in a fresh process and prints its peak memory beyond the scene's.

use std::fs::File;
use std::io::{BufReader, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use raystep::raylog::{RaylogReader, raylog};
use raystep::record::record_pixel;
use raystep::scene::{Scene, load};

const LINES: usize = 1_000_000;
const SIZE: u32 = 512;
const RUNS: usize = 5;
/// Set in the child run: the log it reads once to measure memory.
const MEMORY_RUN: &str = "RAYSTEP_RAYLOG_BENCH_LOG";

fn scene() -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/spd/balls.nff");
    load(&path).unwrap().with_size(SIZE, SIZE).unwrap()
}

/// raystep's own log of `scene`, pixel after pixel, until `LINES` lines.
fn write_log(scene: &Scene, path: &Path) -> usize {
    let mut out = BufWriter::new(File::create(path).unwrap());
    let mut lines = 0;
    'pixels: for y in 0..scene.height {
        for x in 0..scene.width {
            let log = raylog(&record_pixel(scene, &scene.settings, x, y));
            out.write_all(log.as_bytes()).unwrap();
            lines += log.lines().count();
            if lines >= LINES {
                break 'pixels;
            }
        }
    }
    out.flush().unwrap();
    assert!(lines >= LINES, "{lines} lines: the scene is too small");
    lines
}

/// Reads `log` whole; the number of rays.
fn read(log: &Path, scene: &Scene) -> usize {
    let input = BufReader::with_capacity(1 << 16, File::open(log).unwrap());
    let mut rays = 0;
    for ray in RaylogReader::new("LOG", input, scene) {
        std::hint::black_box(ray.unwrap());
        rays += 1;
    }
    rays
}

/// A field of /proc/self/status, in KiB.
fn status_kib(field: &str) -> u64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap();
    let line = status.lines().find(|l| l.starts_with(field)).unwrap();
    line.split_whitespace().nth(1).unwrap().parse().unwrap()
}

/// The child run: load the scene, reset the peak (so the scene's loading
/// does not count), read the log once, print the peak beyond the resident
/// memory before reading.
fn measure_memory(log: &Path) {
    let scene = scene();
    // "5" resets VmHWM to the current resident size (Linux 4.0 on).
    std::fs::write("/proc/self/clear_refs", "5").unwrap();
    let before = status_kib("VmRSS:");
    let rays = read(log, &scene);
    let peak = status_kib("VmHWM:");
    let beyond = (peak - before) as f64;
    println!(
        "{rays} rays read; resident before reading {:.1} MiB, peak {:.1} MiB: \
         {:.1} MiB beyond the scene's, {:.1} bytes per ray",
        before as f64 / 1024.0,
        peak as f64 / 1024.0,
        beyond / 1024.0,
        beyond * 1024.0 / rays as f64
    );
}

fn main() {
    if let Some(log) = std::env::var_os(MEMORY_RUN) {
        return measure_memory(&PathBuf::from(log));
    }
    // `cargo test --benches` runs this without `--bench`: too long for a test.
    if !std::env::args().any(|a| a == "--bench") {
        return;
    }
    let scene = scene();
    let directory = tempfile::tempdir().unwrap();
    let log = directory.path().join("million.jsonl");
    let lines = write_log(&scene, &log);
    let bytes = std::fs::metadata(&log).unwrap().len();
    println!("log: {lines} lines, {:.0} MB", bytes as f64 / 1e6);
    read(&log, &scene);
    let mut seconds: Vec<f64> = (0..RUNS)
        .map(|_| {
            let started = Instant::now();
            read(&log, &scene);
            started.elapsed().as_secs_f64()
        })
        .collect();
    seconds.sort_by(f64::total_cmp);
    println!(
        "read whole: median {:.3} s of {RUNS} (min {:.3}, max {:.3})",
        seconds[RUNS / 2],
        seconds[0],
        seconds[RUNS - 1]
    );
    let child = Command::new(std::env::current_exe().unwrap())
        .env(MEMORY_RUN, &log)
        .output()
        .unwrap();
    assert!(child.status.success(), "{child:?}");
    print!("peak memory: {}", String::from_utf8_lossy(&child.stdout));
}
