//! The command line: clap's definitions in `args.rs`, and one file per
//! command's body (`render.rs`, `inspect.rs`, `explain.rs`, `compare.rs`,
//! `diagram.rs`, `grade.rs`; the debugger is `crate::tui::run`). The three commands on
//! one pixel share `recorded.rs`: the scene loaded, `--set` applied and
//! the pixel recorded.

use std::path::Path;
use std::process::ExitCode;

use anyhow::{Context, Result};

use raystep_engine::printable::printable_text;
use raystep_engine::scene::{self, Scene};

mod args;
mod compare;
mod diagram;
mod explain;
mod grade;
mod inspect;
mod recorded;
mod render;
mod usage;

pub use args::*;
pub use usage::parse_or_exit;

/// Loads a scene (or the built-in one) and applies `--size`.
pub(crate) fn load_scene(path: Option<&Path>, size: SizeArg) -> Result<Scene> {
    let scene = scene::builtin::load_file_or_builtin(path)?;
    for warning in &scene.warnings {
        eprintln!("warning: {}", printable_text(warning));
    }
    Ok(match size.size {
        Some((w, h)) => scene.with_size(w, h)?,
        None => scene,
    })
}

pub fn run(cli: Cli) -> Result<ExitCode> {
    match cli.command {
        Some(Command::Render(args)) => render::run(&args),
        Some(Command::Inspect(args)) => inspect::run(&args),
        Some(Command::Explain(args)) => explain::run(&args),
        Some(Command::Compare(args)) => compare::run(&args),
        Some(Command::Diagram(args)) => diagram::run(&args),
        Some(Command::Grade(args)) => grade::run(&args),
        Some(Command::Debug(args)) => debug(&args),
        None => debug(&cli.debug),
    }
}

/// `raystep [debug] [SCENE] [--compare IMAGE.png] [--pixel X,Y] [--rays LOG.jsonl]`.
fn debug(args: &DebugArgs) -> Result<ExitCode> {
    crate::tui::run(crate::tui::Opening {
        scene: args.scene.as_deref(),
        compare: args.compare.as_deref(),
        pixel: args.pixel,
        rays: args.rays.as_deref(),
        size: args.size,
    })
}

/// Writes to stdout; a reader that closed the pipe early (`| head`) is not an error.
fn emit(text: &str) -> Result<()> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
            Err(e).context("cannot write to stdout")
        }
        _ => Ok(()),
    }
}

/// As `emit`, for output written piece by piece through a buffer (a
/// recording's JSON can run to a gigabyte: it is never held whole).
fn emit_with(write: impl FnOnce(&mut dyn std::io::Write) -> std::io::Result<()>) -> Result<()> {
    use std::io::Write;
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    match write(&mut out).and_then(|()| out.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
            Err(e).context("cannot write to stdout")
        }
        _ => Ok(()),
    }
}

/// Writes text meant for a terminal to stdout: no control character from a
/// name reaches it raw (see `raystep_engine::printable`).
fn emit_text(text: &str) -> Result<()> {
    emit(&printable_text(text))
}
