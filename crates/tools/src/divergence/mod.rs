//! `compare --rays`: a student's ray log beside raystep's own trees, pixel
//! by pixel, down to the first ray and the first number where the two
//! tracers part (docs/RAYLOG.md). The log streams: the first pixels are
//! kept whole and reported in full, the rest are compared ray by ray as
//! they come and only counted.

mod absence;
mod checks;
mod held;
mod kind;
mod meaning;
mod miss_t;
mod moment;
mod ours;
mod pixel_report;
mod size_guess;
mod tolerance;
mod verdict;
mod words;

use std::collections::HashMap;
use std::io::BufRead;

pub use checks::{Check, Value};
pub use held::{CATALOGUE_RAYS, CountedOnly, HELD_RAYS};
pub use kind::Kind;
pub use moment::Field;
pub use ours::OurRays;
pub use pixel_report::compare_pixel;
pub use pixel_report::{AlignedRay, Consistent, Divergence, PixelReport, RayStatus, Unpaired};
pub use tolerance::Tolerance;
pub use words::value_text;
pub use words::{consistent_lines, json, text};

use crate::raylog::{LoggedRay, RaylogError, RaylogReader};
use raystep_engine::scene::Scene;

/// The pixels reported in full; the rest are counted.
pub const PIXELS_SHOWN: usize = 64;

/// The rays in one tree only kept per pixel shown, each with its rule in
/// words; the rest are counted (`PixelReport::unpaired_total`).
pub const UNPAIRED_KEPT: usize = 256;

/// Our trees kept for the counted pixels: a log usually holds a pixel's
/// rays together, so a few suffice; out of order, a tree is recorded again.
const TREES_KEPT: usize = 8;

/// Everything `compare --rays` found.
pub struct LogComparison {
    /// The first `PIXELS_SHOWN` pixels of the log, in the order they first
    /// appear in it.
    pub pixels: Vec<PixelReport>,
    /// Every pixel of the log, and those whose rays all match ours.
    pub pixel_count: usize,
    pub matching: usize,
    /// The pixels whose rays differ from ours but whose colour agrees:
    /// their rays differ where they add nothing.
    pub colour_agreeing: usize,
    /// The image size every primary ray of the log fits, when it is not
    /// the size the log was read at: "pass --size WxH".
    pub traced_at: Option<(u32, u32)>,
    pub rays_read: usize,
    /// The first few unknown keys, printable and cut short (`UnknownKeys`).
    pub unknown_keys: Vec<String>,
    /// How many distinct unknown keys, and whether only at least that many.
    pub unknown_key_count: (usize, bool),
    pub tolerance: Tolerance,
    /// Whether the catalogue's budget (`CATALOGUE_RAYS`) ran out before
    /// every mistake was tried at every pixel shown.
    pub catalogue_stopped: bool,
}

/// A counted pixel's rays so far.
#[derive(Default)]
struct Tally {
    /// Our rays of the pixel, and how many of them the log has.
    ours: usize,
    logged: usize,
    differs: bool,
    /// Whether the primary ray's logged colour agrees with ours.
    colour_agrees: Option<bool>,
}

/// The pixels past the first `PIXELS_SHOWN`, compared ray by ray as they
/// come: on a thread of its own, beside the one reading the log.
struct Counter<'a> {
    scene: &'a Scene,
    tolerance: Tolerance,
    tallies: HashMap<(u32, u32), Tally>,
    trees: Vec<OurRays>,
}

impl Counter<'_> {
    fn count(&mut self, ray: &LoggedRay) {
        let pixel = ray.pixel;
        let at = match self.trees.iter().position(|t| t.tree.pixel == pixel) {
            Some(at) => at,
            None => {
                if self.trees.len() == TREES_KEPT {
                    self.trees.remove(0);
                }
                self.trees
                    .push(OurRays::record(self.scene, &self.scene.settings, pixel));
                self.trees.len() - 1
            }
        };
        let ours = &self.trees[at];
        let tally = self.tallies.entry(pixel).or_default();
        tally.ours = ours.rays().len();
        match ours.find(&ray.path) {
            Some(found) => {
                tally.logged += 1;
                let our_ray = &ours.rays()[found];
                tally.differs |= !checks::all_agree(ray, our_ray, &self.tolerance);
                if ray.path.steps.is_empty()
                    && let (Some(yours), Some(theirs)) = (ray.color, our_ray.color)
                {
                    tally.colour_agrees = Some(self.tolerance.colours(yours, theirs));
                }
            }
            None => tally.differs = true,
        }
    }

    fn matching(&self) -> usize {
        self.tallies
            .values()
            .filter(|t| !t.differs && t.logged == t.ours)
            .count()
    }

    fn colour_agreeing(&self) -> usize {
        self.tallies
            .values()
            .filter(|t| (t.differs || t.logged != t.ours) && t.colour_agrees == Some(true))
            .count()
    }
}

/// Rays handed to the counting thread at a time, and batches in flight:
/// enough to keep both threads busy, few enough to bound the memory.
const BATCH: usize = 4096;
const BATCHES_IN_FLIGHT: usize = 4;

/// Reads the whole log and compares it with `scene` as written.
pub fn compare_log<R: BufRead>(
    scene: &Scene,
    mut reader: RaylogReader<R>,
    tolerance: Tolerance,
) -> Result<LogComparison, RaylogError> {
    let mut shown: Vec<((u32, u32), Vec<LoggedRay>, CountedOnly)> = Vec::new();
    let mut holding = held::Holding::new(scene);
    let mut shown_at: HashMap<(u32, u32), usize> = HashMap::new();
    let mut rays_read = 0;
    let mut size = size_guess::SizeGuess::new(scene);
    let new_counter = || Counter {
        scene,
        tolerance,
        tallies: HashMap::new(),
        trees: Vec::new(),
    };
    let (read, counter) = std::thread::scope(|threads| {
        let (send, receive) = std::sync::mpsc::sync_channel::<Vec<LoggedRay>>(BATCHES_IN_FLIGHT);
        let counting = std::thread::Builder::new().spawn_scoped(threads, move || {
            let mut counter = new_counter();
            for batch in receive {
                for ray in &batch {
                    counter.count(ray);
                }
            }
            counter
        });
        // Where no thread can be started (the web page), rays are counted
        // as they are read.
        let mut inline = counting.is_err().then(new_counter);
        let mut hand_over = |batch: Vec<LoggedRay>| match &mut inline {
            Some(counter) => batch.iter().for_each(|ray| counter.count(ray)),
            // The counter only stops when this thread does.
            None => drop(send.send(batch)),
        };
        let mut batch = Vec::with_capacity(BATCH);
        let read = (|| {
            for item in reader.by_ref() {
                let (_, mut ray) = item?;
                rays_read += 1;
                size.see(&ray);
                let at = match shown_at.get(&ray.pixel) {
                    Some(&at) => Some(at),
                    None if shown.len() < PIXELS_SHOWN => {
                        // No pixel is counted before the shown ones are all found.
                        shown_at.insert(ray.pixel, shown.len());
                        shown.push((ray.pixel, Vec::new(), CountedOnly::default()));
                        Some(shown.len() - 1)
                    }
                    None => None,
                };
                if let Some(at) = at {
                    let (_, rays, counted) = &mut shown[at];
                    if !holding.too_deep(&ray, counted) && holding.take(rays.len(), counted) {
                        rays.push(ray);
                    }
                } else {
                    holding.shallow(&mut ray);
                    batch.push(ray);
                    if batch.len() == BATCH {
                        hand_over(std::mem::replace(&mut batch, Vec::with_capacity(BATCH)));
                    }
                }
            }
            Ok(())
        })();
        if read.is_ok() && !batch.is_empty() {
            hand_over(batch);
        }
        drop(send);
        let counter = match counting {
            Ok(thread) => thread.join().expect("the counting thread does not panic"),
            Err(_) => inline.expect("counted here when no thread was started"),
        };
        (read, counter)
    });
    read?;
    let unknown_keys = reader.unknown_keys().listed().map(String::from).collect();
    let unknown_key_count = reader.unknown_keys().count();
    let mut budget = held::CatalogueBudget::new(CATALOGUE_RAYS);
    let mut pixels: Vec<PixelReport> = shown
        .into_iter()
        .map(|(pixel, yours, counted)| {
            let ours = OurRays::record(scene, &scene.settings, pixel);
            let mut report = pixel_report::compare_within(
                scene,
                (yours, counted),
                &ours,
                &tolerance,
                &mut budget,
                UNPAIRED_KEPT,
            );
            report.aligned = Vec::new();
            report
        })
        .collect();
    verdict::decide(scene, &mut pixels, &tolerance, &mut budget);
    let matching = pixels.iter().filter(|p| p.matches).count() + counter.matching();
    let colour_agreeing = pixels
        .iter()
        .filter(|p| p.differs_where_it_adds_nothing())
        .count()
        + counter.colour_agreeing();
    Ok(LogComparison {
        colour_agreeing,
        traced_at: size.traced_at(),
        pixel_count: pixels.len() + counter.tallies.len(),
        pixels,
        matching,
        rays_read,
        unknown_keys,
        unknown_key_count,
        tolerance,
        catalogue_stopped: budget.stopped,
    })
}
