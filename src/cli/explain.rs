//! `raystep explain`: in plain words, why one pixel has its colour.

use std::process::ExitCode;

use anyhow::Result;

use super::recorded::record;
use super::{PixelArgs, emit_text};
use raystep_engine::record::explain;

pub(super) fn run(args: &PixelArgs) -> Result<ExitCode> {
    let recorded = record(args)?;
    emit_text(&(explain(&recorded.tree) + &recorded.what_changed()))?;
    Ok(ExitCode::SUCCESS)
}
