//! `raystep compare`: the student's render against raystep's, as a report
//! or JSON, with the error map and the graders' thresholds.

use std::process::ExitCode;

use anyhow::Result;

use super::{CompareArgs, CompareFormat, SizeArg, emit, load_scene};
use crate::output;

/// Exit status of `compare` when a `--max-*` threshold is exceeded.
const OVER_THRESHOLD: u8 = 3;

pub(super) fn run(args: &CompareArgs) -> Result<ExitCode> {
    let student = crate::compare::student::load(&args.image)?;
    let (width, height) = student.image.dimensions();
    let scene = load_scene(
        Some(&args.scene),
        SizeArg {
            size: Some((width, height)),
        },
    )?;
    let diff = args.output.as_deref().map(output::file).transpose()?;
    if let Some(diff) = &diff {
        output::refuse_clashes(&args.scene, &[(diff, "the error map (-o)".to_owned())])?;
        output::refuse_input(diff, &args.image, "your image")?;
    }
    let comparison = crate::compare::compare(&scene, student);
    if let Some(diff) = diff {
        output::write_all(None, std::iter::once((&diff, comparison.error_map.clone())))?;
    }
    match args.format {
        CompareFormat::Text => emit(&crate::compare::text(
            &comparison,
            &args.image.display().to_string(),
            &args.scene.display().to_string(),
        ))?,
        CompareFormat::Json => emit(&format!("{}\n", serde_json::to_string_pretty(&comparison)?))?,
    }
    let m = &comparison.metrics;
    let over = args.max_flip.is_some_and(|f| m.flip_mean > f)
        || args.max_mean_abs.is_some_and(|e| m.mean_abs > e);
    Ok(if over {
        ExitCode::from(OVER_THRESHOLD)
    } else {
        ExitCode::SUCCESS
    })
}
