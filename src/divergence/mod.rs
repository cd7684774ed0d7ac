//! `compare --rays`: a student's ray log beside raystep's own trees, pixel
//! by pixel, down to the first ray and the first number where the two
//! tracers part (docs/RAYLOG.md). The log streams: the first pixels are
//! kept whole and reported in full, the rest are compared ray by ray as
//! they come and only counted.

mod absence;
mod checks;
mod kind;
mod meaning;
mod moment;
mod ours;
mod pixel_report;
mod tolerance;
mod words;

use std::collections::HashMap;
use std::io::BufRead;

pub use checks::{Check, Value};
pub use kind::Kind;
pub use moment::Field;
pub(crate) use ours::OurRays;
pub(crate) use pixel_report::compare_pixel;
pub use pixel_report::{AlignedRay, Divergence, PixelReport, RayStatus, Unpaired};
pub use tolerance::Tolerance;
pub(crate) use words::value_text;
pub use words::{json, text};

use crate::raylog::{LoggedRay, RaylogError, RaylogReader};
use crate::scene::Scene;

/// The pixels reported in full; the rest are counted.
pub const PIXELS_SHOWN: usize = 64;

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
    pub rays_read: usize,
    pub unknown_keys: Vec<String>,
    pub tolerance: Tolerance,
}

/// A counted pixel's rays so far.
#[derive(Default)]
struct Tally {
    /// Our rays of the pixel, and how many of them the log has.
    ours: usize,
    logged: usize,
    differs: bool,
}

/// Reads the whole log and compares it with `scene` as written.
pub fn compare_log<R: BufRead>(
    scene: &Scene,
    mut reader: RaylogReader<R>,
    tolerance: Tolerance,
) -> Result<LogComparison, RaylogError> {
    let mut shown: Vec<((u32, u32), Vec<LoggedRay>)> = Vec::new();
    let mut shown_at: HashMap<(u32, u32), usize> = HashMap::new();
    let mut counted: HashMap<(u32, u32), Tally> = HashMap::new();
    let mut trees: Vec<OurRays> = Vec::new();
    let mut rays_read = 0;
    for item in reader.by_ref() {
        let (_, ray) = item?;
        rays_read += 1;
        let pixel = ray.pixel;
        if let Some(&at) = shown_at.get(&pixel) {
            shown[at].1.push(ray);
            continue;
        }
        if shown.len() < PIXELS_SHOWN && !counted.contains_key(&pixel) {
            shown_at.insert(pixel, shown.len());
            shown.push((pixel, vec![ray]));
            continue;
        }
        let ours = match trees.iter().position(|t| t.tree.pixel == pixel) {
            Some(at) => &trees[at],
            None => {
                if trees.len() == TREES_KEPT {
                    trees.remove(0);
                }
                trees.push(OurRays::record(scene, &scene.settings, pixel));
                &trees[trees.len() - 1]
            }
        };
        let tally = counted.entry(pixel).or_default();
        tally.ours = ours.rays().len();
        match ours.find(&ray.path) {
            Some(at) => {
                tally.logged += 1;
                let checked = checks::checks(&ray, &ours.rays()[at], &tolerance);
                tally.differs |= checked.iter().any(|c| !c.agrees);
            }
            None => tally.differs = true,
        }
    }
    let unknown_keys = reader.unknown_keys().iter().cloned().collect();
    let pixels: Vec<PixelReport> = shown
        .into_iter()
        .map(|(pixel, yours)| {
            let ours = OurRays::record(scene, &scene.settings, pixel);
            compare_pixel(scene, yours, &ours, &tolerance)
        })
        .collect();
    let matching = pixels.iter().filter(|p| p.matches).count()
        + counted
            .values()
            .filter(|t| !t.differs && t.logged == t.ours)
            .count();
    Ok(LogComparison {
        pixel_count: pixels.len() + counted.len(),
        pixels,
        matching,
        rays_read,
        unknown_keys,
        tolerance,
    })
}
