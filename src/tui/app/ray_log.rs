//! `--rays`: the student's ray log, read once at open, and the pixel traced
//! set beside it. The log's first pixels are kept whole (as `compare
//! --rays` reports them); the pixel shown is compared again with the tree
//! as it is traced now, so that a toggle or a mistake turned on shows
//! whether it makes your rays and ours agree. That comparison runs in the
//! background (`compare_job.rs`): until it is back, the pixel is shown as
//! being compared. `y` goes from logged pixel to logged pixel.

use std::io::BufReader;
use std::path::Path;
use std::sync::Arc;

use anyhow::{Result, bail};

use raystep_engine::record::{RayTree, count};
use raystep_engine::scene::Scene;
use raystep_model::mistakes::Mistake;
use raystep_tools::divergence::{Consistent, LogComparison, PixelReport, Tolerance, compare_log};
use raystep_tools::raylog::{LoggedRay, RaylogReader};

use crate::tui::compare_job::{Comparer, Request};

/// Your rays of one pixel, shared with the comparing thread.
type YourRays = Arc<Vec<LoggedRay>>;

/// What is said of a logged pixel while it is being compared.
pub(super) const COMPARING: &str = "comparing your rays with ours…";

pub struct RayLog {
    /// The log's file, as given.
    name: String,
    /// The pixels kept whole, in the order they first appear in the log,
    /// each with your rays (shared with the comparing thread).
    pixels: Vec<((u32, u32), YourRays)>,
    /// The log's verdict on each of those pixels, as `compare --rays`
    /// gives it: the mistakes named, and those it is only consistent with.
    verdicts: Vec<(Vec<Mistake>, Vec<Consistent>)>,
    /// Every pixel of the log, those kept whole and those only counted.
    pixel_count: usize,
    rays_read: usize,
    tolerance: Tolerance,
    /// The logged pixel `y` went to last.
    at: Option<usize>,
    /// The pixel traced beside your rays of it; `None` when it is not in
    /// the log, or while it is being compared.
    report: Option<PixelReport>,
    /// Compares the pixel shown in the background.
    comparer: Comparer,
    /// Each pixel or settings followed is a new generation; results of
    /// older ones are dropped.
    generation: u64,
    /// Whether the pixel shown is logged and its comparison not back yet.
    comparing: bool,
    /// The log's verdict (the mistakes it is traced as, and in words), when
    /// a logged pixel differs: it overrides the image's (issue 39).
    verdict: Option<(Vec<raystep_model::mistakes::Mistake>, String)>,
}

impl RayLog {
    /// Reads the log at `path` against `scene` (its size, lights and
    /// objects); a bad log is the reader's `LOG:line:column: problem`.
    pub fn read(scene: &Scene, path: &Path) -> Result<RayLog> {
        let name = path.display().to_string();
        if path == Path::new("-") {
            bail!("the debugger reads its keys from stdin: give the ray log as a file, not -");
        }
        let file =
            raystep_engine::input_file::open(path, "the ray log", raystep_tools::raylog::LOG_CAP)?;
        let reader = RaylogReader::new(name.clone(), BufReader::new(file), scene);
        let comparison = compare_log(scene, reader, Tolerance::default())?;
        Ok(RayLog::of(name, comparison))
    }

    fn of(name: String, comparison: LogComparison) -> RayLog {
        let verdicts = (comparison.pixels.iter())
            .map(|p| (p.mistakes.clone(), p.consistent.clone()))
            .collect();
        let verdict = raystep_tools::compare::log_verdict(&comparison);
        RayLog {
            verdict,
            name,
            verdicts,
            pixels: (comparison.pixels.into_iter())
                .map(|p| (p.pixel, Arc::new(p.yours)))
                .collect(),
            pixel_count: comparison.pixel_count,
            rays_read: comparison.rays_read,
            tolerance: comparison.tolerance,
            at: None,
            report: None,
            comparer: Comparer::new(false),
            generation: 0,
            comparing: false,
        }
    }

    /// The log comparing on the caller's thread when `sync` (tests), so
    /// that a pixel's report is ready when `follow` returns.
    pub(super) fn comparing_in(mut self, sync: bool) -> RayLog {
        self.comparer = Comparer::new(sync);
        self
    }

    /// Whether the pixel shown is logged and still being compared.
    pub fn comparing(&self) -> bool {
        self.comparing
    }

    /// The mistake the pixel shown is named with, or else consistent
    /// with: where `M` opens.
    pub(crate) fn mistake_shown(&self) -> Option<Mistake> {
        let report = self.report.as_ref()?;
        (report.mistakes.first().copied()).or(report.consistent.first().map(|c| c.mistake))
    }

    /// The log's verdict, when a logged pixel differs.
    pub(super) fn verdict(&self) -> Option<&(Vec<Mistake>, String)> {
        self.verdict.as_ref()
    }

    /// The pixel traced beside your rays of it, when it is in the log.
    pub fn report(&self) -> Option<&PixelReport> {
        self.report.as_ref()
    }

    /// Compares `tree`, the pixel as traced now, with your rays of it, in
    /// the background: the report is there once `collect` has taken it in
    /// (at once when comparing on the caller's thread).
    pub(super) fn follow(&mut self, tree: &RayTree, scene: Arc<Scene>) {
        self.generation += 1;
        self.report = None;
        let logged = self
            .pixels
            .iter()
            .position(|(pixel, _)| *pixel == tree.pixel);
        self.comparing = logged.is_some();
        if let Some(at) = logged {
            self.comparer.request(Request {
                generation: self.generation,
                scene,
                tree: tree.clone(),
                yours: self.pixels[at].1.clone(),
                tolerance: self.tolerance,
                verdict: self.verdicts[at].clone(),
            });
            self.collect();
        }
    }

    /// Takes in the comparison of the pixel shown once it is back; whether
    /// it came now. Those of pixels or settings since left are dropped.
    pub(super) fn collect(&mut self) -> bool {
        let mut came = false;
        while let Some((generation, report)) = self.comparer.poll() {
            if generation == self.generation {
                self.report = Some(report);
                self.comparing = false;
                came = true;
            }
        }
        came
    }

    /// `y` (`delta` 1) or `Y` (-1): the logged pixel after or before the
    /// cursor's (or the last one gone to), cycling.
    pub(super) fn step(&mut self, cursor: (u32, u32), delta: i32) -> (u32, u32) {
        let count = self.pixels.len() as i64;
        if count == 0 {
            return cursor;
        }
        let here = self.pixels.iter().position(|(pixel, _)| *pixel == cursor);
        let next = match here.or(self.at) {
            Some(at) => (at as i64 + delta as i64).rem_euclid(count) as usize,
            None if delta < 0 => self.pixels.len() - 1,
            None => 0,
        };
        self.at = Some(next);
        self.pixels[next].0
    }

    /// The first logged pixel, where the debugger opens.
    pub(super) fn first_pixel(&mut self) -> Option<(u32, u32)> {
        let (pixel, _) = self.pixels.first()?;
        self.at = Some(0);
        Some(*pixel)
    }

    /// The status line's words on the pixel shown: which logged pixel it
    /// is and how it compares.
    pub(super) fn pixel_words(&self, cursor: (u32, u32)) -> String {
        let (x, y) = cursor;
        let Some(at) = self.pixels.iter().position(|(pixel, _)| *pixel == cursor) else {
            return format!("pixel ({x}, {y}) is not in your log: y goes to a logged pixel");
        };
        let shown = self.pixels.len();
        let of = if self.pixel_count > shown {
            format!("of the first {shown} ({} in the log)", self.pixel_count)
        } else {
            format!("of {shown}")
        };
        let how = match self
            .report
            .as_ref()
            .and_then(|r| r.first_divergence.as_ref())
        {
            None if self.comparing => COMPARING.to_string(),
            None => "your rays match ours".to_string(),
            Some(d) => format!("first differs at {} {}, D goes there", d.path, d.field),
        };
        format!("logged pixel {} {of}, ({x}, {y}): {how}", at + 1)
    }

    /// The status line's words at open.
    pub(super) fn opening_words(&self, cursor: (u32, u32)) -> String {
        let logged = self.pixels.iter().any(|(pixel, _)| *pixel == cursor);
        format!(
            "{} ({}, {}): {}{}",
            self.name,
            count(self.pixel_count as u64, "pixel", "pixels"),
            count(self.rays_read as u64, "ray", "rays"),
            self.pixel_words(cursor),
            if logged { "; y: next" } else { "" }
        )
    }
}
