//! `raystep inspect`: one pixel's ray tree with every term, as text, JSON,
//! Graphviz or a ray log.

use std::process::ExitCode;

use anyhow::Result;

use super::recorded::record;
use super::{InspectArgs, InspectFormat, emit, emit_text, emit_with};
use raystep_engine::record::{dot, text, write_json};
use raystep_tools::raylog::raylog;

pub(super) fn run(args: &InspectArgs) -> Result<ExitCode> {
    let recorded = record(&args.pixel)?;
    let tree = &recorded.tree;
    match args.format {
        InspectFormat::Text => emit_text(&(text(tree) + &recorded.what_changed()))?,
        InspectFormat::Json => {
            // serde_json would print a NaN or an infinity as `null`: refuse instead.
            tree.check_finite().map_err(|e| {
                anyhow::anyhow!(
                    "pixel {:?}: cannot write the recording as JSON: {e}",
                    tree.pixel
                )
            })?;
            // Streamed: a tree of 65,536 rays is a gigabyte of JSON.
            emit_with(|out| write_json(tree, out).map_err(std::io::Error::from))?
        }
        InspectFormat::Dot => emit(&dot(tree))?,
        InspectFormat::Raylog => emit(&raylog(tree))?,
    }
    Ok(ExitCode::SUCCESS)
}
