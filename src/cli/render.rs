//! `raystep render`: the whole image to PNG, with its term images, ray
//! counts and timings when asked.

use std::io::IsTerminal;
use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

use anyhow::{Context, Result};

use super::{RenderArgs, emit, load_scene};
use raystep_engine::render::{render, with_threads};
use raystep_engine::scene::{Scene, Settings};
use raystep_engine::terms::{Term, TermImages, render_terms};
use raystep_engine::trace::{NoRecorder, RayStats};
use raystep_tools::output::{self, Target};

/// The image, its stats when `stats`, and the term images when `terms`: one
/// trace, as the terms pass gives the image (and the stats) too.
fn trace_image(
    (scene, settings): (&Scene, &Settings),
    stats: bool,
    terms: bool,
    tick: &(dyn Fn() + Sync),
) -> (image::RgbImage, RayStats, Option<TermImages>) {
    match (stats, terms) {
        (true, true) => {
            let (terms, stats) = render_terms::<RayStats>(scene, settings, tick);
            (terms.color_image(), stats, Some(terms))
        }
        (false, true) => {
            let (terms, _) = render_terms::<NoRecorder>(scene, settings, tick);
            (terms.color_image(), RayStats::default(), Some(terms))
        }
        (true, false) => {
            let (image, stats) = render::<RayStats>(scene, settings, tick);
            (image, stats, None)
        }
        (false, false) => (
            render::<NoRecorder>(scene, settings, tick).0,
            RayStats::default(),
            None,
        ),
    }
}

pub(super) fn run(args: &RenderArgs) -> Result<ExitCode> {
    let started = Instant::now();
    if args.threads.is_none() {
        // Start the worker threads now, so that they are up by the time
        // the scene is parsed rather than when tracing begins.
        rayon::spawn(|| {});
    }
    let scene = load_scene(Some(&args.scene), args.size)?;
    let settings = args.mistakes.settings(&scene)?;
    let outputs = Outputs::check(args, &scene)?;
    let prepared = started.elapsed().as_secs_f64();
    let progress = progress_bar(scene.height);
    let tick = || progress.inc(1);
    let threads = args.threads.map(usize::from);
    let traced = Instant::now();
    let want_terms = outputs.terms.is_some();
    let (image, stats, terms) = with_threads(threads, || {
        trace_image((&scene, &settings), args.stats, want_terms, &tick)
    })?;
    let tracing = traced.elapsed().as_secs_f64();
    progress.finish_and_clear();
    let term_images = terms.iter().flat_map(|terms| {
        outputs
            .term_files
            .iter()
            .map(|(term, target)| (target, terms.image(*term)))
    });
    output::write_all(
        outputs.terms.as_ref(),
        std::iter::once((&outputs.image, image)).chain(term_images),
    )?;
    if args.stats || args.timings {
        let mut json = if args.stats {
            serde_json::to_value(stats).context("cannot write stats")?
        } else {
            serde_json::json!({})
        };
        if let (true, Some(terms)) = (args.stats, &terms) {
            // The scales of the two false-colour term images.
            for (key, term) in [
                ("rays_per_pixel", Term::Rays),
                ("cost_per_pixel", Term::Cost),
            ] {
                let (min, max) = terms.count_range(term);
                json[key] = serde_json::json!({ "min": min, "max": max });
            }
        }
        json["width"] = scene.width.into();
        json["height"] = scene.height.into();
        json["objects"] = scene.objects.len().into();
        json["lights"] = scene.lights.len().into();
        if args.stats && !scene.warnings.is_empty() {
            // What reading the scene's meshes warned about (MODEL §4).
            json["warnings"] = scene.warnings.clone().into();
        }
        json["threads"] = threads.unwrap_or_else(rayon::current_num_threads).into();
        json["prepare_seconds"] = prepared.into();
        json["trace_seconds"] = tracing.into();
        if let Some(peak) = peak_memory_mib() {
            json["peak_memory_mib"] = peak.into();
        }
        emit(&format!("{json}\n"))?;
    }
    Ok(ExitCode::SUCCESS)
}

/// Where `render` writes, checked before the render starts (see `output`).
struct Outputs {
    image: Target,
    terms: Option<output::Folder>,
    /// One per `Term::written_for` the scene, when `--terms` is given.
    term_files: Vec<(Term, Target)>,
}

impl Outputs {
    fn check(args: &RenderArgs, scene: &Scene) -> Result<Outputs> {
        let image = output::file(&args.output)?;
        let terms = args.terms.as_deref().map(output::folder).transpose()?;
        let term_files = match &terms {
            Some(folder) => Term::written_for(scene)
                .into_iter()
                .map(|term| Ok((term, folder.file(&term.file_name())?)))
                .collect::<Result<_>>()?,
            None => Vec::new(),
        };
        let terms_dir = args.terms.as_deref().unwrap_or(Path::new("")).display();
        let all: Vec<_> = std::iter::once((&image, "the image (-o)".to_owned()))
            .chain(term_files.iter().map(|(term, file)| {
                (
                    file,
                    format!("the {} image of --terms {terms_dir}", term.name()),
                )
            }))
            .collect();
        output::refuse_clashes(&output::Inputs::default().with_scene(scene), &all)?;
        Ok(Outputs {
            image,
            terms,
            term_files,
        })
    }
}

/// The process's peak resident memory so far (Linux `VmHWM`), in MiB.
fn peak_memory_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}

/// A progress bar on stderr when it is a terminal; hidden otherwise.
fn progress_bar(rows: u32) -> indicatif::ProgressBar {
    if !std::io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(rows.into());
    if let Ok(style) = indicatif::ProgressStyle::with_template(
        "{spinner} rendering {bar:40} {pos}/{len} rows {elapsed}",
    ) {
        bar.set_style(style);
    }
    bar
}
