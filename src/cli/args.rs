//! What the command line takes: clap's definitions of every subcommand and
//! option, and the parsers of their values. What each command then does is
//! in the file named after it.

use std::path::PathBuf;

use clap::builder::PossibleValue;
use clap::{Args, Parser, Subcommand, ValueEnum};

use raystep_engine::scene::{self, Scene, Settings};
use raystep_model::mistakes::{Mistake, Mistakes};

/// raystep: a step-through debugger for Whitted ray tracing.
///
/// Without a subcommand it opens the debugger on SCENE, or on a built-in
/// scene when none is given.
#[derive(Parser, Debug)]
#[command(version, about, args_conflicts_with_subcommands = true)]
// `raystep [SCENE]` says its arguments as it always has: for the debugger.
#[command(
    mut_arg("scene", |a| a.help("Scene file for the debugger (.toml or .nff)")),
    mut_arg("compare", |a| a.help(
        "Compare with your own render of the scene (a PNG): its views, regions \
         and the mistakes that explain it, in the debugger"
    )),
    mut_arg("pixel", |a| a.help(
        "Open the debugger on the pixel X,Y (x to the right, y downward, from 0)"
    )),
    mut_arg("rays", |a| a.help(
        "Your tracer's ray log (docs/RAYLOG.md): each logged pixel's rays marked \
         against ours in the debugger, opening on the first"
    )),
)]
pub struct Cli {
    #[command(subcommand)]
    pub(crate) command: Option<Command>,
    /// Without a subcommand: the debugger, as `raystep debug` opens it.
    #[command(flatten)]
    pub(crate) debug: DebugArgs,
}

impl Cli {
    /// Flag combinations clap cannot refuse itself, as they depend on a
    /// flag's value (`--plane crossing` with `--zoom 2`): a usage error,
    /// which exits with status 2 as clap's own do.
    pub(crate) fn check_combinations(&self) -> Result<(), clap::Error> {
        let Some(Command::Diagram(args)) = &self.command else {
            return Ok(());
        };
        let message = if args.plane == PlaneArg::Crossing && args.zoom != 1.0 {
            "--zoom magnifies the top, side and ray diagrams; the crossing figure is always fitted to its polygon"
        } else if args.plane == PlaneArg::Crossing && args.shadows != ShadowsArg::All {
            "--shadows chooses the top, side and ray diagrams' shadow rays; the crossing figure has none"
        } else {
            return Ok(());
        };
        let mut cli = <Cli as clap::CommandFactory>::command();
        cli.build();
        let diagram = cli
            .find_subcommand_mut("diagram")
            .expect("diagram is a subcommand");
        Err(diagram.error(clap::error::ErrorKind::ArgumentConflict, message))
    }
}

/// The debugger's arguments, the same for `raystep [SCENE]` and
/// `raystep debug [SCENE]`.
#[derive(Args, Debug)]
pub(crate) struct DebugArgs {
    /// Scene file (.toml or .nff); the built-in scene when absent.
    pub(crate) scene: Option<PathBuf>,
    /// Compare with your own render of the scene (a PNG), traced at its
    /// size: its views, regions and the mistakes that explain it.
    #[arg(long, value_name = "IMAGE.png")]
    pub(crate) compare: Option<PathBuf>,
    /// Open on the pixel X,Y (x to the right, y downward, from 0).
    #[arg(long, value_name = "X,Y", value_parser = parse_pixel, allow_hyphen_values = true)]
    pub(crate) pixel: Option<(u32, u32)>,
    /// Your tracer's ray log (docs/RAYLOG.md), its pixels at the size
    /// traced: each logged pixel's rays marked against ours, opening on
    /// the first.
    #[arg(long, value_name = "LOG.jsonl")]
    pub(crate) rays: Option<PathBuf>,
    /// Trace the scene at WIDTHxHEIGHT (the field of view is kept), and
    /// read the log's pixels at it: a log traced at another size than the
    /// scene's. With --compare, it must be the image's size.
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub(crate) size: Option<(u32, u32)>,
}

#[derive(Subcommand, Debug)]
pub(crate) enum Command {
    /// Open the interactive debugger.
    Debug(DebugArgs),
    /// Render a whole image to PNG.
    Render(RenderArgs),
    /// Print one pixel's ray tree with every term.
    Inspect(InspectArgs),
    /// Explain in plain words why one pixel has its colour.
    Explain(PixelArgs),
    /// Compare your own render of a scene with raystep's: how far apart,
    /// where, and which classic mistake explains the difference; with
    /// --rays, your tracer's rays beside ours, down to the first number
    /// that differs.
    Compare(CompareArgs),
    /// Draw one pixel's rays as an SVG figure for a slide.
    Diagram(DiagramArgs),
    /// Grade a class's renders against an assignment's scenes (one folder
    /// per student) into a report folder; or one student's folder, for an
    /// autograder's container, with Gradescope's or PrairieLearn's results.
    Grade(GradeArgs),
}

#[derive(Args, Debug)]
pub(crate) struct GradeArgs {
    /// The assignment file (TOML): its scenes, the file each student hands
    /// in for each, and the points (docs/TEACHERS.md).
    pub(crate) assignment: PathBuf,
    /// The students' folders, one per student (SUBMISSIONS/<student>/glass.png).
    #[arg(
        value_name = "SUBMISSIONS",
        required_unless_present = "submission",
        conflicts_with = "submission",
        requires = "output"
    )]
    pub(crate) submissions: Option<PathBuf>,
    /// The report folder: new, or a previous report, replaced whole.
    #[arg(short, long, value_name = "REPORT")]
    pub(crate) output: Option<PathBuf>,
    /// Grade one student's folder alone (an autograder's container): a
    /// summary on stdout, and the results files asked for.
    #[arg(long, value_name = "DIR")]
    pub(crate) submission: Option<PathBuf>,
    /// With --submission: write Gradescope's results.json here.
    #[arg(long, value_name = "RESULTS.json", requires = "submission")]
    pub(crate) gradescope: Option<PathBuf>,
    /// With --submission: write PrairieLearn's results.json here.
    #[arg(long, value_name = "RESULTS.json", requires = "submission")]
    pub(crate) prairielearn: Option<PathBuf>,
    /// Worker threads (default: all cores); the grades are the same
    /// whatever it says.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=1024))]
    pub(crate) jobs: Option<u16>,
}

/// A figure draws one scene: `--diff-against` (another scene's recording,
/// told as text by `inspect` and `explain`) is refused, not ignored, and
/// hidden from diagram's help; `--set` draws the changed scene.
#[derive(Args, Debug)]
#[command(
    mut_arg("diff_against", |a| a.hide(true).value_parser(no_diff_against)),
    mut_arg("set", |a| a.help(
        "What-if: change a setting or a material's number first, e.g. \
         `settings.max_depth=2` or `materials.glass.ior=1.0` (repeatable); the \
         figure is drawn with the changed scene, and its title names each change"
    )),
)]
pub(crate) struct DiagramArgs {
    #[command(flatten)]
    pub(crate) pixel: PixelArgs,
    /// The SVG file to write (new, or a regular file to replace).
    #[arg(short, long, value_name = "FIG.svg")]
    pub(crate) output: PathBuf,
    /// The plane drawn, in the camera's frame: from above, from the side,
    /// or the primary ray's plane of incidence; or `crossing`, the (U, V)
    /// plane of the crossing test of the first polygon hit (or passed by).
    #[arg(long, value_enum, default_value_t = PlaneArg::Top)]
    pub(crate) plane: PlaneArg,
    /// Magnify the figure F times (F >= 1) about the primary ray's first
    /// hit; what falls outside is cut at the edge. 1 shows everything.
    /// Not for `crossing`.
    #[arg(long, value_name = "F", default_value_t = 1.0, value_parser = zoom_factor, allow_hyphen_values = true)]
    pub(crate) zoom: f64,
    /// Which shadow rays are drawn, for a slide about something else:
    /// every hit's (`all`), only the primary ray's hit's (`primary`), or
    /// none (`none`, nor the blockers' × and the dotted lines to lights
    /// facing away).
    #[arg(long, value_enum, default_value_t = ShadowsArg::All)]
    pub(crate) shadows: ShadowsArg,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum ShadowsArg {
    All,
    Primary,
    None,
}

/// `diagram --diff-against`: always refused, saying what to do instead.
fn no_diff_against(_: &str) -> std::result::Result<PathBuf, String> {
    Err(
        "a figure draws one scene, so diagram takes no --diff-against: \
         draw each scene's figure, or see what changed with `raystep explain --diff-against`"
            .to_owned(),
    )
}

/// The largest `--zoom`: far past any slide's need, and small enough that
/// every coordinate in the figure stays finite (1e308 made NaNs).
pub(crate) const MAX_ZOOM: f64 = 1e4;

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
pub(crate) enum PlaneArg {
    Top,
    Side,
    Ray,
    Crossing,
}

#[derive(Args, Debug)]
pub(crate) struct CompareArgs {
    /// Scene file (.toml or .nff); rendered at the image's size.
    pub(crate) scene: PathBuf,
    /// Your render of the scene, a PNG (alpha and 16 bits are converted).
    /// Optional with --rays.
    #[arg(required_unless_present = "rays")]
    pub(crate) image: Option<PathBuf>,
    /// Your tracer's rays, a ray log (docs/RAYLOG.md; `-` reads stdin):
    /// each logged pixel's rays beside ours, down to the first number
    /// that differs.
    #[arg(long, value_name = "LOG.jsonl")]
    pub(crate) rays: Option<PathBuf>,
    /// The image size the log's pixels belong to, WIDTHxHEIGHT (default:
    /// the image's, else the scene's). Only with --rays.
    #[arg(long, value_name = "WxH", value_parser = parse_size, requires = "rays")]
    pub(crate) size: Option<(u32, u32)>,
    /// When two logged numbers agree: GEOMETRY (relative, on positions,
    /// directions and t; default 1e-4) and optionally COLOUR (absolute,
    /// on colours, terms, S and weights; default 1/512). Only with --rays.
    #[arg(long, value_name = "GEOMETRY[,COLOUR]", value_parser = raystep_tools::divergence::Tolerance::parse, requires = "rays")]
    pub(crate) tolerance: Option<raystep_tools::divergence::Tolerance>,
    /// Output form: a report for people, or JSON for graders.
    #[arg(long, value_enum, default_value_t = CompareFormat::Text)]
    pub(crate) format: CompareFormat,
    /// Also write FLIP's error map (magma colours) to this PNG.
    #[arg(short, long, value_name = "DIFF.png")]
    pub(crate) output: Option<PathBuf>,
    /// Exit with status 3 when FLIP's mean error is above F (a number
    /// from 0 up).
    #[arg(long, value_name = "F", value_parser = threshold, allow_hyphen_values = true)]
    pub(crate) max_flip: Option<f64>,
    /// Exit with status 3 when the mean absolute error is above E (a
    /// number from 0 up).
    #[arg(long, value_name = "E", value_parser = threshold, allow_hyphen_values = true)]
    pub(crate) max_mean_abs: Option<f64>,
}

/// `--max-flip` and `--max-mean-abs`: a finite number of at least 0. Both
/// errors run from 0 up, so NaN (every comparison with it is false: no
/// image would ever be over) or a negative number (every image would be,
/// even an identical one) cannot be what a grader meant.
fn threshold(text: &str) -> std::result::Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(f) if f.is_finite() && f >= 0.0 => Ok(f),
        _ => Err(format!(
            "{text:?} is not a threshold: give a number of at least 0, such as 0.05"
        )),
    }
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum CompareFormat {
    Text,
    Json,
}

#[derive(Args, Debug)]
pub(crate) struct PixelArgs {
    /// Scene file (.toml or .nff).
    pub(crate) scene: PathBuf,
    /// The pixel X,Y (x to the right, y downward, from 0).
    #[arg(long, value_name = "X,Y", value_parser = parse_pixel, allow_hyphen_values = true)]
    pub(crate) pixel: (u32, u32),
    #[command(flatten)]
    pub(crate) size: SizeArg,
    #[command(flatten)]
    pub(crate) mistakes: MistakeArgs,
    /// What-if: change a setting or a material's number first, e.g.
    /// `settings.max_depth=2` or `materials.glass.ior=1.0` (repeatable); the
    /// text then ends with what changed against the scene as written.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub(crate) set: Vec<String>,
    /// Also record the pixel in ORIGINAL (another scene file, at the same
    /// size) and end the text with what changed from it.
    #[arg(long, value_name = "ORIGINAL")]
    pub(crate) diff_against: Option<PathBuf>,
}

#[derive(Args, Debug)]
pub(crate) struct InspectArgs {
    #[command(flatten)]
    pub(crate) pixel: PixelArgs,
    /// Output form: an indented tree, the complete recording as JSON,
    /// Graphviz, or a ray log (docs/RAYLOG.md: one JSON line per ray).
    #[arg(long, value_enum, default_value_t = InspectFormat::Text)]
    pub(crate) format: InspectFormat,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum InspectFormat {
    Text,
    Json,
    Dot,
    Raylog,
}

#[derive(Args, Debug)]
pub(crate) struct RenderArgs {
    /// Scene file (.toml or .nff).
    pub(crate) scene: PathBuf,
    /// Output PNG file: new, or a regular file to replace (a link is
    /// followed); never the scene, a directory or a device.
    #[arg(short, long)]
    pub(crate) output: PathBuf,
    #[command(flatten)]
    pub(crate) size: SizeArg,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = clap::value_parser!(u16).range(1..=1024))]
    pub(crate) threads: Option<u16>,
    /// Print ray counts and timings as one JSON object on stdout.
    #[arg(long, conflicts_with = "timings")]
    pub(crate) stats: bool,
    /// Print only the timings and peak memory as one JSON object on stdout:
    /// those of a plain render, which counts nothing (what benchmarks time).
    #[arg(long)]
    pub(crate) timings: bool,
    /// Also write one PNG per term (ambient, emission when some material
    /// emits, diffuse, specular, reflected, transmitted, shadow, rays, cost)
    /// into this directory, created if missing; all the files are replaced
    /// together or none is.
    #[arg(long, value_name = "DIR")]
    pub(crate) terms: Option<PathBuf>,
    #[command(flatten)]
    pub(crate) mistakes: MistakeArgs,
}

#[derive(Args, Debug, Clone)]
pub(crate) struct MistakeArgs {
    /// Trace with this classic student mistake (repeatable; README and
    /// docs/MODEL.md §8 list them), to make the wrong image on purpose.
    #[arg(long = "mistake", value_name = "NAME", value_enum)]
    pub(crate) mistakes: Vec<MistakeName>,
}

impl MistakeArgs {
    /// The scene's settings with these mistakes; refused when the scene's
    /// profile does not offer one (`Profile::offers`): it could change
    /// nothing, and an image made "with" it would say it did.
    pub(crate) fn settings(&self, scene: &Scene) -> anyhow::Result<Settings> {
        let profile = scene.settings.profile;
        for MistakeName(mistake) in &self.mistakes {
            if let Some(why) = profile.why_not_offered(*mistake) {
                anyhow::bail!("--mistake {mistake} {why}");
            }
        }
        Ok(Settings {
            mistakes: self.mistakes.iter().map(|m| m.0).collect::<Mistakes>(),
            ..scene.settings
        })
    }
}

/// A mistake named on the command line: the catalogue's fixed names are
/// the option's values. (The catalogue lives in the lecture crate, which
/// knows no command line.)
#[derive(Clone, Copy, Debug)]
pub(crate) struct MistakeName(pub(crate) Mistake);

const MISTAKE_NAMES: [MistakeName; Mistake::ALL.len()] = {
    let mut names = [MistakeName(Mistake::ALL[0]); Mistake::ALL.len()];
    let mut i = 0;
    while i < names.len() {
        names[i] = MistakeName(Mistake::ALL[i]);
        i += 1;
    }
    names
};

impl ValueEnum for MistakeName {
    fn value_variants<'a>() -> &'a [Self] {
        &MISTAKE_NAMES
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        Some(PossibleValue::new(self.0.name()))
    }
}

#[derive(Args, Debug, Clone, Copy)]
pub(crate) struct SizeArg {
    /// Image size WIDTHxHEIGHT, overriding the scene's (the field of view is kept).
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub(crate) size: Option<(u32, u32)>,
}

/// Parses `WxH`, e.g. `320x240`.
pub(crate) fn parse_size(text: &str) -> Result<(u32, u32), String> {
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
pub(crate) fn parse_pixel(text: &str) -> Result<(u32, u32), String> {
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
