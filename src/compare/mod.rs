//! `raystep compare`: a student's render against raystep's own, down to the
//! mistake and the ray that shows it. The metrics say how far apart the
//! images are; the regions say where; the terms of the reference's recording
//! say what a region's difference looks like; the mistakes, rendered with the
//! same engine, say which classic error explains it.

mod diagnosis;
pub mod metrics;
mod ranking;
mod reference;
pub mod regions;
mod report;
pub mod student;

use image::RgbImage;
use serde::Serialize;

pub use metrics::{MATCH_SHARE, Metrics, TOLERANCE_STEPS};
pub use ranking::{MIN_FIT, Ranked};
pub use report::text;
pub use student::StudentImage;

use crate::record::{RayTree, explain_unwrapped, record_pixel};
use crate::scene::Scene;

/// The regions a report describes; the rest are only counted.
const REGIONS_SHOWN: usize = 5;
/// The objects named for a region; the rest are counted.
const OBJECTS_SHOWN: usize = 3;
/// How many of a region's pixels the term diagnosis looks at.
const DIAGNOSIS_SAMPLES: usize = 24;

/// Everything `compare` found.
#[derive(Serialize)]
pub struct Comparison {
    pub width: u32,
    pub height: u32,
    /// What was converted to read the student's image.
    pub notes: Vec<String>,
    pub metrics: Metrics,
    /// At most `MATCH_SHARE` of the pixels past the tolerance.
    pub matches: bool,
    /// How many connected regions of differing pixels there are.
    pub region_count: usize,
    /// The largest regions, largest first.
    pub regions: Vec<RegionReport>,
    /// The mistakes that explain the difference, best first; empty when the
    /// images match.
    pub mistakes: Vec<Ranked>,
    /// FLIP's error map in magma colours.
    #[serde(skip)]
    pub error_map: RgbImage,
}

/// One region of differing pixels, with a pixel that represents it.
#[derive(Serialize)]
pub struct RegionReport {
    pub pixels: usize,
    /// x0, y0, x1, y1, inclusive.
    pub bounds: [u32; 4],
    /// The objects the reference's primary rays hit there, most pixels
    /// first: the first `OBJECTS_SHOWN`.
    pub objects: Vec<ObjectShare>,
    /// How many more objects the region covers.
    pub more_objects: usize,
    /// The region's pixel with the largest difference.
    pub pixel: [u32; 2],
    pub yours: [u8; 3],
    pub reference: [u8; 3],
    /// The reference's recording of that pixel in brief, as `explain` says it.
    pub explain: Vec<String>,
    /// Which term the difference looks like, when one fits most of the
    /// region's sampled pixels.
    pub diagnosis: Option<String>,
}

#[derive(Serialize)]
pub struct ObjectShare {
    /// The object's name, or "background".
    pub object: String,
    pub pixels: usize,
}

/// Compares the student's image with `scene` rendered at the image's size
/// with the scene's own settings.
pub fn compare(scene: &Scene, student: StudentImage) -> Comparison {
    let yours = student.image;
    let settings = scene.settings;
    let reference = reference::render(scene, &settings);
    let (metrics, error_map) = metrics::measure(&yours, &reference.image);
    let matches = metrics.matches();
    let found = regions::regions(&metrics::over_tolerance(&yours, &reference.image));
    let regions = found
        .iter()
        .take(REGIONS_SHOWN)
        .map(|region| describe(scene, &reference, &yours, region))
        .collect();
    let mistakes = if matches {
        Vec::new()
    } else {
        ranking::rank(scene, &settings, &yours, &reference.image)
    };
    Comparison {
        width: yours.width(),
        height: yours.height(),
        notes: student.notes,
        metrics,
        matches,
        region_count: found.len(),
        regions,
        mistakes,
        error_map,
    }
}

fn describe(
    scene: &Scene,
    reference: &reference::Reference,
    yours: &RgbImage,
    region: &regions::Region,
) -> RegionReport {
    let gap = |&(x, y): &(u32, u32)| {
        metrics::channel_gap(yours.get_pixel(x, y).0, reference.image.get_pixel(x, y).0)
    };
    // The largest gap; the first in row-major order among equals.
    let &(x, y) = region
        .pixels
        .iter()
        .rev()
        .max_by_key(|p| gap(p))
        .expect("a region has pixels");
    let tree = record_pixel(scene, &scene.settings, x, y);
    let (x0, y0, x1, y1) = region.bounds();
    let objects = objects(scene, reference, region);
    RegionReport {
        pixels: region.pixels.len(),
        bounds: [x0, y0, x1, y1],
        more_objects: objects.len().saturating_sub(OBJECTS_SHOWN),
        objects: objects.into_iter().take(OBJECTS_SHOWN).collect(),
        pixel: [x, y],
        yours: yours.get_pixel(x, y).0,
        reference: reference.image.get_pixel(x, y).0,
        explain: brief(&explain_unwrapped(&tree)),
        diagnosis: diagnosis::diagnose(&samples(scene, yours, region)),
    }
}

/// Pixels spread evenly over a region (all of a small one), each recorded.
fn samples(scene: &Scene, yours: &RgbImage, region: &regions::Region) -> Vec<(RayTree, [u8; 3])> {
    let step = region.pixels.len().div_ceil(DIAGNOSIS_SAMPLES);
    region
        .pixels
        .iter()
        .step_by(step.max(1))
        .map(|&(x, y)| {
            let tree = record_pixel(scene, &scene.settings, x, y);
            (tree, yours.get_pixel(x, y).0)
        })
        .collect()
}

/// How many of the region's pixels show each object, most first.
fn objects(
    scene: &Scene,
    reference: &reference::Reference,
    region: &regions::Region,
) -> Vec<ObjectShare> {
    let mut counts: Vec<(Option<usize>, usize)> = Vec::new();
    for &(x, y) in &region.pixels {
        let object = reference.object_at(x, y);
        match counts.iter_mut().find(|(o, _)| *o == object) {
            Some((_, n)) => *n += 1,
            None => counts.push((object, 1)),
        }
    }
    counts.sort_by_key(|&(_, n)| std::cmp::Reverse(n));
    counts
        .into_iter()
        .map(|(object, pixels)| ObjectShare {
            object: object.map_or("background".into(), |o| scene.object_name(o).to_string()),
            pixels,
        })
        .collect()
}

/// `explain`'s sentence on the primary ray and its three largest terms.
fn brief(explained: &str) -> Vec<String> {
    let lines: Vec<&str> = explained.lines().collect();
    // The sentence itself, not the near misses `explain` puts before it.
    let mut out: Vec<String> = lines
        .iter()
        .find(|l| l.starts_with("Its primary ray"))
        .map(|l| l.to_string())
        .into_iter()
        .collect();
    if let Some(start) = lines
        .iter()
        .position(|l| l.starts_with("Its colour is the sum"))
    {
        out.extend(
            lines[start + 1..]
                .iter()
                .take(3)
                .map(|l| l.trim().to_string()),
        );
    }
    out
}
