//! The command line: what each subcommand takes, and how it runs.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use anyhow::{Context, Result, bail};
use clap::builder::PossibleValue;
use clap::{Args, Parser, Subcommand, ValueEnum};

use crate::mistakes::{Mistake, Mistakes};
use crate::output::{self, Target};
use crate::record::{RayTree, dot, explain, record_pixel, text};
use crate::render::{render, with_threads};
use crate::scene::{self, Scene, Settings};
use crate::terms::{Term, TermImages, render_terms};
use crate::trace::{NoRecorder, RayStats};

/// raystep: a step-through debugger for Whitted ray tracing.
///
/// Without a subcommand it opens the debugger on SCENE, or on a built-in
/// scene when none is given.
#[derive(Parser, Debug)]
#[command(version, about, args_conflicts_with_subcommands = true)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    /// Scene file for the debugger (.toml or .nff).
    pub scene: Option<PathBuf>,
    /// Compare with your own render of the scene (a PNG): its views, regions
    /// and the mistakes that explain it, in the debugger.
    #[arg(long, value_name = "IMAGE.png")]
    pub compare: Option<PathBuf>,
    /// Open the debugger on the pixel X,Y (x to the right, y downward, from 0).
    #[arg(long, value_name = "X,Y", value_parser = parse_pixel, allow_hyphen_values = true)]
    pub pixel: Option<(u32, u32)>,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Open the interactive debugger.
    Debug {
        /// Scene file (.toml or .nff); the built-in scene when absent.
        scene: Option<PathBuf>,
        /// Compare with your own render of the scene (a PNG), traced at its
        /// size: its views, regions and the mistakes that explain it.
        #[arg(long, value_name = "IMAGE.png")]
        compare: Option<PathBuf>,
        /// Open on the pixel X,Y (x to the right, y downward, from 0).
        #[arg(long, value_name = "X,Y", value_parser = parse_pixel, allow_hyphen_values = true)]
        pixel: Option<(u32, u32)>,
    },
    /// Render a whole image to PNG.
    Render(RenderArgs),
    /// Print one pixel's ray tree with every term.
    Inspect(InspectArgs),
    /// Explain in plain words why one pixel has its colour.
    Explain(PixelArgs),
    /// Compare your own render of a scene with raystep's: how far apart,
    /// where, and which classic mistake explains the difference.
    Compare(CompareArgs),
    /// Draw one pixel's rays as an SVG figure for a slide.
    Diagram(DiagramArgs),
}

#[derive(Args, Debug)]
pub struct DiagramArgs {
    #[command(flatten)]
    pub pixel: PixelArgs,
    /// The SVG file to write (new, or a regular file to replace).
    #[arg(short, long, value_name = "FIG.svg")]
    pub output: PathBuf,
    /// The plane drawn, in the camera's frame: from above, from the side,
    /// or the primary ray's plane of incidence; or `crossing`, the (U, V)
    /// plane of the crossing test of the first polygon hit (or passed by).
    #[arg(long, value_enum, default_value_t = PlaneArg::Top)]
    pub plane: PlaneArg,
    /// Magnify the figure F times (F >= 1) about the primary ray's first
    /// hit; what falls outside is cut at the edge. 1 shows everything.
    /// Not for `crossing`.
    #[arg(long, value_name = "F", default_value_t = 1.0, value_parser = zoom_factor, allow_hyphen_values = true)]
    pub zoom: f64,
}

/// The largest `--zoom`: far past any slide's need, and small enough that
/// every coordinate in the figure stays finite (1e308 made NaNs).
pub const MAX_ZOOM: f64 = 1e4;

/// `--zoom`: a factor from 1 to `MAX_ZOOM`.
fn zoom_factor(text: &str) -> std::result::Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(f) if (1.0..=MAX_ZOOM).contains(&f) => Ok(f),
        _ => Err(format!(
            "{text:?} is not a zoom factor: give a number from 1 to {MAX_ZOOM}, such as 3"
        )),
    }
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlaneArg {
    Top,
    Side,
    Ray,
    Crossing,
}

#[derive(Args, Debug)]
pub struct CompareArgs {
    /// Scene file (.toml or .nff); rendered at the image's size.
    pub scene: PathBuf,
    /// Your render of the scene, a PNG (alpha and 16 bits are converted).
    pub image: PathBuf,
    /// Output form: a report for people, or JSON for graders.
    #[arg(long, value_enum, default_value_t = CompareFormat::Text)]
    pub format: CompareFormat,
    /// Also write FLIP's error map (magma colours) to this PNG.
    #[arg(short, long, value_name = "DIFF.png")]
    pub output: Option<PathBuf>,
    /// Exit with status 3 when FLIP's mean error is above F.
    #[arg(long, value_name = "F")]
    pub max_flip: Option<f64>,
    /// Exit with status 3 when the mean absolute error is above E.
    #[arg(long, value_name = "E")]
    pub max_mean_abs: Option<f64>,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum CompareFormat {
    Text,
    Json,
}

#[derive(Args, Debug)]
pub struct PixelArgs {
    /// Scene file (.toml or .nff).
    pub scene: PathBuf,
    /// The pixel X,Y (x to the right, y downward, from 0).
    #[arg(long, value_name = "X,Y", value_parser = parse_pixel, allow_hyphen_values = true)]
    pub pixel: (u32, u32),
    #[command(flatten)]
    pub size: SizeArg,
    #[command(flatten)]
    pub mistakes: MistakeArgs,
    /// What-if: change a setting or a material's number first, e.g.
    /// `settings.max_depth=2` or `materials.glass.ior=1.0` (repeatable); the
    /// text then ends with what changed against the scene as written.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Also record the pixel in ORIGINAL (another scene file, at the same
    /// size) and end the text with what changed from it.
    #[arg(long, value_name = "ORIGINAL")]
    pub diff_against: Option<PathBuf>,
}

#[derive(Args, Debug)]
pub struct InspectArgs {
    #[command(flatten)]
    pub pixel: PixelArgs,
    /// Output form: an indented tree, the complete recording as JSON, or Graphviz.
    #[arg(long, value_enum, default_value_t = InspectFormat::Text)]
    pub format: InspectFormat,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum InspectFormat {
    Text,
    Json,
    Dot,
}

#[derive(Args, Debug)]
pub struct RenderArgs {
    /// Scene file (.toml or .nff).
    pub scene: PathBuf,
    /// Output PNG file: new, or a regular file to replace (a link is
    /// followed); never the scene, a directory or a device.
    #[arg(short, long)]
    pub output: PathBuf,
    #[command(flatten)]
    pub size: SizeArg,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = clap::value_parser!(u16).range(1..=1024))]
    pub threads: Option<u16>,
    /// Print ray counts and timings as one JSON object on stdout.
    #[arg(long, conflicts_with = "timings")]
    pub stats: bool,
    /// Print only the timings and peak memory as one JSON object on stdout:
    /// those of a plain render, which counts nothing (what benchmarks time).
    #[arg(long)]
    pub timings: bool,
    /// Also write one PNG per term (ambient, diffuse, specular, reflected,
    /// transmitted, shadow, rays, cost) into this directory, created if
    /// missing; all the files are replaced together or none is.
    #[arg(long, value_name = "DIR")]
    pub terms: Option<PathBuf>,
    #[command(flatten)]
    pub mistakes: MistakeArgs,
}

#[derive(Args, Debug, Clone)]
pub struct MistakeArgs {
    /// Trace with this classic student mistake (repeatable; README and
    /// docs/MODEL.md §8 list them), to make the wrong image on purpose.
    #[arg(long = "mistake", value_name = "NAME", value_enum)]
    pub mistakes: Vec<Mistake>,
}

impl MistakeArgs {
    /// The scene's settings with these mistakes.
    pub fn settings(&self, scene: &Scene) -> Settings {
        Settings {
            mistakes: self.mistakes.iter().copied().collect::<Mistakes>(),
            ..scene.settings
        }
    }
}

/// The catalogue's fixed names are the option's values.
impl ValueEnum for Mistake {
    fn value_variants<'a>() -> &'a [Self] {
        &Mistake::ALL
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        Some(PossibleValue::new(self.name()))
    }
}

#[derive(Args, Debug, Clone, Copy)]
pub struct SizeArg {
    /// Image size WIDTHxHEIGHT, overriding the scene's (the field of view is kept).
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub size: Option<(u32, u32)>,
}

/// Parses `WxH`, e.g. `320x240`.
pub fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let bad = || format!("`{text}` is not a size: expected WIDTHxHEIGHT, e.g. 320x240");
    let (w, h) = text.split_once(['x', 'X']).ok_or_else(bad)?;
    let (w, h) = (
        w.trim().parse().map_err(|_| bad())?,
        h.trim().parse().map_err(|_| bad())?,
    );
    scene::check_image_size(w, h)?;
    Ok((w, h))
}

/// Parses `X,Y`, e.g. `160,120`.
pub fn parse_pixel(text: &str) -> Result<(u32, u32), String> {
    let bad =
        || format!("`{text}` is not a pixel: expected X,Y with whole numbers from 0, e.g. 160,120");
    let (x, y) = text.split_once(',').ok_or_else(bad)?;
    let coordinate = |c: &str| -> Result<u32, String> {
        match c.trim().parse::<i64>() {
            Ok(n) if n < 0 => Err(format!(
                "`{text}` is not a pixel: {n} is negative, and pixels are counted from 0"
            )),
            _ => c.trim().parse().map_err(|_| bad()),
        }
    };
    Ok((coordinate(x)?, coordinate(y)?))
}

/// Loads a scene (or the built-in one) and applies `--size`.
pub fn load_scene(path: Option<&Path>, size: SizeArg) -> Result<Scene> {
    let scene = scene::builtin::load_file_or_builtin(path)?;
    Ok(match size.size {
        Some((w, h)) => scene.with_size(w, h)?,
        None => scene,
    })
}

pub fn run(cli: Cli) -> Result<ExitCode> {
    match cli.command {
        Some(Command::Render(args)) => render_command(&args),
        Some(Command::Inspect(args)) => inspect_command(&args),
        Some(Command::Explain(args)) => explain_command(&args),
        Some(Command::Compare(args)) => compare_command(&args),
        Some(Command::Diagram(args)) => diagram_command(&args),
        Some(Command::Debug {
            scene,
            compare,
            pixel,
        }) => crate::tui::run(scene.as_deref(), compare.as_deref(), pixel),
        None => crate::tui::run(cli.scene.as_deref(), cli.compare.as_deref(), cli.pixel),
    }
}

/// The pixel's recording, and for `--set` or `--diff-against` the one it
/// is compared with and what that was.
struct Recorded {
    scene: Scene,
    tree: RayTree,
    before: Option<(RayTree, String)>,
}

impl Recorded {
    /// What changed against the recording before, as a closing section.
    fn what_changed(&self) -> String {
        match &self.before {
            None => String::new(),
            Some((before, what)) => format!(
                "\nWhat changed against {what}:\n{}",
                crate::record::diff(before, &self.tree)
            ),
        }
    }
}

/// Loads the scene and records the pixel, refusing one outside the image;
/// with `--set`, the changed scene, and the scene as written beside it.
fn record(args: &PixelArgs) -> Result<Recorded> {
    let mut scene = load_scene(Some(&args.scene), args.size)?;
    let (x, y) = args.pixel;
    if x >= scene.width || y >= scene.height {
        bail!(
            "pixel ({x}, {y}) is outside the {}x{} image: x must be below {} and y below {}",
            scene.width,
            scene.height,
            scene.width,
            scene.height
        );
    }
    let before = match &args.diff_against {
        Some(original) => {
            let other = scene::builtin::load_file_or_builtin(Some(original))?
                .with_size(scene.width, scene.height)?;
            Some((other, original.display().to_string()))
        }
        None if !args.set.is_empty() => Some((scene.clone(), "the scene as written".to_string())),
        None => None,
    };
    for assignment in &args.set {
        scene::overrides::apply(&mut scene, assignment).map_err(anyhow::Error::msg)?;
    }
    let record = |scene: &Scene| record_pixel(scene, &args.mistakes.settings(scene), x, y);
    Ok(Recorded {
        tree: record(&scene),
        scene,
        before: before.map(|(other, what)| (record(&other), what)),
    })
}

fn inspect_command(args: &InspectArgs) -> Result<ExitCode> {
    let recorded = record(&args.pixel)?;
    let tree = &recorded.tree;
    match args.format {
        InspectFormat::Text => emit(&(text(tree) + &recorded.what_changed()))?,
        InspectFormat::Json => {
            // serde_json would print a NaN or an infinity as `null`: refuse instead.
            tree.check_finite().map_err(|e| {
                anyhow::anyhow!(
                    "pixel {:?}: cannot write the recording as JSON: {e}",
                    tree.pixel
                )
            })?;
            emit(&format!(
                "{}\n",
                serde_json::to_string_pretty(&tree.to_json())?
            ))?
        }
        InspectFormat::Dot => emit(&dot(tree))?,
    }
    Ok(ExitCode::SUCCESS)
}

fn diagram_command(args: &DiagramArgs) -> Result<ExitCode> {
    use crate::diagram::{Diagram, DiagramPlane, Progress, svg};
    let target = output::file(&args.output)?;
    output::refuse_clashes(
        &args.pixel.scene,
        &[(&target, "the figure (-o)".to_owned())],
    )?;
    if args.plane == PlaneArg::Crossing && args.zoom != 1.0 {
        bail!(
            "--zoom magnifies the top, side and ray diagrams; the crossing figure is always fitted to its polygon"
        );
    }
    let recorded = record(&args.pixel)?;
    let plane = match args.plane {
        PlaneArg::Top => DiagramPlane::Top,
        PlaneArg::Side => DiagramPlane::Side,
        PlaneArg::Ray => DiagramPlane::Primary,
        PlaneArg::Crossing => return crossing_figure(&recorded.tree, &target),
    };
    let (scene, tree) = (&recorded.scene, &recorded.tree);
    let figure = svg::figure(
        &Diagram::new(scene, tree, plane, Progress::done(tree)),
        args.zoom,
    );
    output::write_text(&target, &figure)?;
    Ok(ExitCode::SUCCESS)
}

/// `--plane crossing`: the first polygon hit, or else passed by; none is an error.
fn crossing_figure(tree: &RayTree, target: &Target) -> Result<ExitCode> {
    use crate::diagram::svg::crossing;
    let Some(subject) = crossing::subject(tree) else {
        anyhow::bail!(
            "pixel ({}, {}): no ray of its tree hits a polygon or patch or passes one by, \
             so there is no crossing test to draw (try --plane top)",
            tree.pixel.0,
            tree.pixel.1
        );
    };
    output::write_text(target, &crossing::svg(tree.pixel, &subject))?;
    Ok(ExitCode::SUCCESS)
}

fn explain_command(args: &PixelArgs) -> Result<ExitCode> {
    let recorded = record(args)?;
    emit(&(explain(&recorded.tree) + &recorded.what_changed()))?;
    Ok(ExitCode::SUCCESS)
}

/// Exit status of `compare` when a `--max-*` threshold is exceeded.
const OVER_THRESHOLD: u8 = 3;

fn compare_command(args: &CompareArgs) -> Result<ExitCode> {
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

fn render_command(args: &RenderArgs) -> Result<ExitCode> {
    let started = Instant::now();
    if args.threads.is_none() {
        // Start the worker threads now, so that they are up by the time
        // the scene is parsed rather than when tracing begins.
        rayon::spawn(|| {});
    }
    let scene = load_scene(Some(&args.scene), args.size)?;
    let settings = args.mistakes.settings(&scene);
    let outputs = Outputs::check(args)?;
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
        Term::ALL
            .iter()
            .zip(&outputs.term_files)
            .map(|(&term, target)| (target, terms.image(term)))
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
    /// One per `Term::ALL`, when `--terms` is given.
    term_files: Vec<Target>,
}

impl Outputs {
    fn check(args: &RenderArgs) -> Result<Outputs> {
        let image = output::file(&args.output)?;
        let terms = args.terms.as_deref().map(output::folder).transpose()?;
        let term_files = match &terms {
            Some(folder) => Term::ALL
                .iter()
                .map(|term| folder.file(&term.file_name()))
                .collect::<Result<_>>()?,
            None => Vec::new(),
        };
        let terms_dir = args.terms.as_deref().unwrap_or(Path::new("")).display();
        let all: Vec<_> = std::iter::once((&image, "the image (-o)".to_owned()))
            .chain(Term::ALL.iter().zip(&term_files).map(|(term, file)| {
                (
                    file,
                    format!("the {} image of --terms {terms_dir}", term.name()),
                )
            }))
            .collect();
        output::refuse_clashes(&args.scene, &all)?;
        Ok(Outputs {
            image,
            terms,
            term_files,
        })
    }
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
