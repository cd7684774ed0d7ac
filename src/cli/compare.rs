//! `raystep compare`: the student's render against raystep's, as a report
//! or JSON, with the error map and the graders' thresholds; with `--rays`,
//! the student's ray log beside raystep's trees.

use std::io::{BufRead, BufReader};
use std::path::Path;
use std::process::ExitCode;

use anyhow::{Context, Result, bail};

use super::{CompareArgs, CompareFormat, SizeArg, emit, emit_text, load_scene};
use raystep_engine::scene::Scene;
use raystep_tools::compare::Comparison;
use raystep_tools::divergence::{LogComparison, compare_log};
use raystep_tools::output;
use raystep_tools::raylog::RaylogReader;

/// Exit status of `compare` when a `--max-*` threshold is exceeded.
const OVER_THRESHOLD: u8 = 3;

pub(super) fn run(args: &CompareArgs) -> Result<ExitCode> {
    let student = args
        .image
        .as_deref()
        .map(raystep_tools::compare::student::load)
        .transpose()?;
    let image_size = student.as_ref().map(|s| s.image.dimensions());
    if let (Some((w, h)), Some((sw, sh))) = (image_size, args.size)
        && (w, h) != (sw, sh)
    {
        bail!(
            "--size {sw}x{sh} is not your image's size, {w}x{h}: leave --size out to use the image's"
        );
    }
    let scene = load_scene(
        Some(&args.scene),
        SizeArg {
            size: image_size.or(args.size),
        },
    )?;
    let diff = args.output.as_deref().map(output::file).transpose()?;
    if let Some(diff) = &diff {
        let mut inputs = output::Inputs::default().with_scene(&scene);
        if let Some(image) = &args.image {
            inputs = inputs.with(image, "your image");
        }
        if let Some(log) = args.rays.as_deref() {
            inputs = if log == Path::new("-") {
                // `--rays - < rays.jsonl`: that file is an input too.
                inputs.with_stdin("your ray log")
            } else {
                inputs.with(log, "your ray log")
            };
        }
        output::refuse_clashes(&inputs, &[(diff, "the error map (-o)".to_owned())])?;
    }
    // The log is read before the image is compared: a bad log is told at once.
    let rays = args
        .rays
        .as_deref()
        .map(|log| read_log(&scene, log, args.tolerance.unwrap_or_default()))
        .transpose()?;
    let mut comparison = student
        .map(|student| raystep_tools::compare::compare(&scene, student))
        .transpose()?;
    // With a log beside the image, the log's verdict is the one shown.
    if let (Some(comparison), Some(rays)) = (comparison.as_mut(), rays.as_ref()) {
        raystep_tools::compare::supersede_by_log(comparison, rays);
    }
    if let (Some(diff), Some(comparison)) = (diff, &comparison) {
        let map = (comparison.error_map.clone()).context("this build has no FLIP for --diff")?;
        output::write_all(None, std::iter::once((&diff, map)))?;
    }
    let scene_name = args.scene.display().to_string();
    match args.format {
        CompareFormat::Text => {
            emit_text(&text(args, &scene_name, comparison.as_ref(), rays.as_ref()))?
        }
        CompareFormat::Json => emit(&format!("{}\n", json(comparison.as_ref(), rays.as_ref())?))?,
    }
    let over = comparison.as_ref().is_some_and(|c| {
        let m = &c.metrics;
        args.max_flip
            .is_some_and(|f| m.flip_mean.is_some_and(|mean| mean > f))
            || args.max_mean_abs.is_some_and(|e| m.mean_abs > e)
    });
    Ok(if over {
        ExitCode::from(OVER_THRESHOLD)
    } else {
        ExitCode::SUCCESS
    })
}

/// The log compared with the scene; `-` is stdin.
fn read_log(
    scene: &Scene,
    log: &Path,
    tolerance: raystep_tools::divergence::Tolerance,
) -> Result<LogComparison> {
    let name = log.display().to_string();
    let input: Box<dyn BufRead> = if log == Path::new("-") {
        Box::new(BufReader::new(std::io::stdin().lock()))
    } else {
        let file =
            raystep_engine::input_file::open(log, "the ray log", raystep_tools::raylog::LOG_CAP)?;
        Box::new(BufReader::new(file))
    };
    Ok(compare_log(
        scene,
        RaylogReader::new(name, input, scene),
        tolerance,
    )?)
}

fn text(
    args: &CompareArgs,
    scene: &str,
    comparison: Option<&Comparison>,
    rays: Option<&LogComparison>,
) -> String {
    let mut out = String::new();
    if let (Some(comparison), Some(image)) = (comparison, &args.image) {
        out.push_str(&raystep_tools::compare::text(
            comparison,
            &image.display().to_string(),
            scene,
        ));
    }
    if let (Some(rays), Some(log)) = (rays, &args.rays) {
        if !out.is_empty() {
            out.push('\n');
        }
        out.push_str(&raystep_tools::divergence::text(
            rays,
            &log.display().to_string(),
            scene,
            comparison.map(|c| c.matches),
        ));
    }
    out
}

/// The image's JSON as before; the log's on its own, or with the image's
/// beside it under "image".
fn json(comparison: Option<&Comparison>, rays: Option<&LogComparison>) -> Result<String> {
    let image = comparison.map(serde_json::to_value).transpose()?;
    let value = match (rays.map(raystep_tools::divergence::json), image) {
        (Some(mut rays), image) => {
            if let (Some(object), Some(image)) = (rays.as_object_mut(), image) {
                object.insert("image".into(), image);
            }
            rays
        }
        (None, Some(image)) => image,
        (None, None) => serde_json::Value::Null,
    };
    Ok(serde_json::to_string_pretty(&value)?)
}
