//! The student's tracer, `tests/student/whitted.py`, as the tests run it.

use std::process::{Command, Output};

/// The tracer's path from the repository's root.
pub const TRACER: &str = "tests/student/whitted.py";

/// Runs a Python tracer (the student's, or cse167.py) with `args` (the
/// script's path first) from the repository's root; its output once it
/// succeeded.
pub fn run_tracer(args: &[&str]) -> Output {
    let output = Command::new("python3")
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("python3 runs");
    assert!(
        output.status.success(),
        "python3 {args:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    output
}
