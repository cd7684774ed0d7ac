//! `--compare`: the student's image kept beside what `compare` found at
//! open, and `w`, which goes from region to region.

use image::RgbImage;

use raystep_engine::record::count;
use raystep_tools::compare::{Comparison, RegionReport};

/// The student's image, its comparison with the scene (made once, when the
/// app opens), and the region `w` went to last.
pub struct StudentComparison {
    yours: RgbImage,
    comparison: Comparison,
    region: Option<usize>,
}

impl StudentComparison {
    pub(super) fn new(yours: RgbImage, comparison: Comparison) -> StudentComparison {
        StudentComparison {
            yours,
            comparison,
            region: None,
        }
    }

    /// The student's image.
    pub(crate) fn yours(&self) -> &RgbImage {
        &self.yours
    }

    /// The log's verdict overrides the image's: each ranked mistake the log
    /// is not traced as is shown superseded by it.
    pub(super) fn supersede_by_log(
        &mut self,
        traced: &[raystep_model::mistakes::Mistake],
        words: &str,
    ) {
        raystep_tools::compare::supersede_untraced(&mut self.comparison.mistakes, traced, words);
    }

    /// What `compare` found: the ranked mistakes, the regions, the error map.
    pub fn findings(&self) -> &Comparison {
        &self.comparison
    }

    /// `w`: the next region (the largest first, cycling), as its pixel and
    /// what the status line says; or why there is none.
    pub(super) fn next_region(&mut self) -> Result<((u32, u32), String), String> {
        let comparison = &self.comparison;
        let (shown, all) = (comparison.regions.len(), comparison.region_count);
        if shown == 0 {
            return Err("your image matches: no region differs".into());
        }
        let index = self.region.map_or(0, |r| (r + 1) % shown);
        let region = &comparison.regions[index];
        let [x, y] = region.pixel;
        let of = if all > shown {
            format!("of the {shown} largest ({all} in all)")
        } else {
            format!("of {shown}")
        };
        let message = format!(
            "region {} {of}: {} on {} · {}",
            index + 1,
            count(region.pixels as u64, "pixel", "pixels"),
            objects(region),
            diagnosis(region)
        );
        self.region = Some(index);
        Ok(((x, y), message))
    }

    /// "region 2: yours ≈ reference − ambient (...)": the diagnosis of the
    /// region `w` went to last, while `cursor` is inside its box, so it
    /// stays in the status line as the pixel's trace is stepped through.
    pub(crate) fn region_words(&self, (x, y): (u32, u32)) -> Option<String> {
        let index = self.region?;
        let region = self.comparison.regions.get(index)?;
        let [x0, y0, x1, y1] = region.bounds;
        let inside = (x0..=x1).contains(&x) && (y0..=y1).contains(&y);
        inside.then(|| format!("region {}: {}", index + 1, diagnosis(region)))
    }
}

/// The region's diagnosis, as `compare` gives it, or that none was given.
fn diagnosis(region: &RegionReport) -> String {
    (region.diagnosis.clone()).unwrap_or_else(|| "no diagnosis fits".into())
}

/// "glass ball", "floor and glass ball", "floor, wall and 2 more".
fn objects(region: &RegionReport) -> String {
    let mut names: Vec<String> = region.objects.iter().map(|o| o.object.clone()).collect();
    if region.more_objects > 0 {
        names.push(format!("{} more", region.more_objects));
    }
    match names.split_last() {
        Some((last, [])) => last.clone(),
        Some((last, rest)) => format!("{} and {last}", rest.join(", ")),
        None => "nothing".into(),
    }
}
