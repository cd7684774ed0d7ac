//! Reading and comparing a million-line ray log (issue 21: "a log of a
//! million lines compares in bounded memory (at most 64 MiB beyond the
//! scene's) and in under 2 s on 2 cores"). Run with `cargo bench --bench
//! raylog`.
//!
//! Writes raystep's own log of scenes/spd/balls.nff at 512x512 (`raylog`
//! of each pixel's recorded tree, pixels in image order) until it holds a
//! million lines, into a temporary file; times reading it whole with
//! `RaylogReader` (a warm-up, then the median of `RUNS`: one read takes
//! seconds, so criterion's ten samples and warm-up would hold the shared
//! machine for a minute); then this binary runs itself once more to read the
//! log in a fresh process and prints its peak memory beyond the scene's.
//! Then the same for `compare_log`, what `raystep compare --rays` runs: the
//! reading thread and the counting thread, every pixel recorded again and
//! checked ray by ray.

use std::fs::File;
use std::io::{BufReader, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use raystep_engine::record::record_pixel;
use raystep_engine::scene::{Scene, load};
use raystep_tools::divergence::{Tolerance, compare_log};
use raystep_tools::raylog::{RaylogReader, raylog};

const LINES: usize = 1_000_000;
const SIZE: u32 = 512;
const RUNS: usize = 5;
/// Set in the child run: the log it reads once to measure memory, and
/// whether it compares it too.
const MEMORY_RUN: &str = "RAYSTEP_RAYLOG_BENCH_LOG";
const MEMORY_RUN_COMPARES: &str = "RAYSTEP_RAYLOG_BENCH_COMPARE";

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

/// Compares `log` with the scene as `compare --rays` does; the number of
/// pixels, all of which must match (the log is raystep's own).
fn compare(log: &Path, scene: &Scene) -> usize {
    let input = BufReader::with_capacity(1 << 16, File::open(log).unwrap());
    let found = compare_log(
        scene,
        RaylogReader::new("LOG", input, scene),
        Tolerance::default(),
    )
    .unwrap();
    assert_eq!(found.matching, found.pixel_count);
    found.pixel_count
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
    let comparing = std::env::var_os(MEMORY_RUN_COMPARES).is_some();
    let rays = if comparing {
        compare(log, &scene);
        log_lines(log)
    } else {
        read(log, &scene)
    };
    let peak = status_kib("VmHWM:");
    let beyond = (peak - before) as f64;
    println!(
        "{rays} rays {}; resident before {:.1} MiB, peak {:.1} MiB: \
         {:.1} MiB beyond the scene's, {:.1} bytes per ray",
        if comparing { "compared" } else { "read" },
        before as f64 / 1024.0,
        peak as f64 / 1024.0,
        beyond / 1024.0,
        beyond * 1024.0 / rays as f64
    );
}

fn log_lines(log: &Path) -> usize {
    std::io::BufRead::lines(BufReader::new(File::open(log).unwrap())).count()
}

/// The median, least and most of `RUNS` timed runs of `work`, after one
/// untimed run.
fn timed(work: impl Fn()) -> (f64, f64, f64) {
    work();
    let mut seconds: Vec<f64> = (0..RUNS)
        .map(|_| {
            let started = Instant::now();
            work();
            started.elapsed().as_secs_f64()
        })
        .collect();
    seconds.sort_by(f64::total_cmp);
    (seconds[RUNS / 2], seconds[0], seconds[RUNS - 1])
}

/// The child run's report of its peak memory, reading or comparing.
fn peak_memory(log: &Path, comparing: bool) -> String {
    let mut command = Command::new(std::env::current_exe().unwrap());
    command.env(MEMORY_RUN, log);
    if comparing {
        command.env(MEMORY_RUN_COMPARES, "1");
    }
    let child = command.output().unwrap();
    assert!(child.status.success(), "{child:?}");
    String::from_utf8_lossy(&child.stdout).into_owned()
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
    let (median, least, most) = timed(|| {
        read(&log, &scene);
    });
    println!("read whole: median {median:.3} s of {RUNS} (min {least:.3}, max {most:.3})");
    print!("peak memory: {}", peak_memory(&log, false));
    let (median, least, most) = timed(|| {
        compare(&log, &scene);
    });
    println!("compare_log: median {median:.3} s of {RUNS} (min {least:.3}, max {most:.3})");
    print!("peak memory: {}", peak_memory(&log, true));
}
