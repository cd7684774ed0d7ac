//! `--compare`: the student's image kept beside what `compare` found at
//! open, and `w`, which takes the cursor from region to region.

use image::RgbImage;

use super::App;
use crate::compare::{Comparison, RegionReport};

/// The student's image and the comparison, made once when the app opens.
pub struct Compared {
    pub yours: RgbImage,
    pub comparison: Comparison,
}

impl App {
    /// The cursor to the next region's pixel (the largest first, cycling).
    pub(super) fn next_region(&mut self) {
        let Some(comparison) = self.comparison() else {
            self.message = Some("no image to compare: open with --compare IMAGE.png".into());
            return;
        };
        let (shown, all) = (comparison.regions.len(), comparison.region_count);
        if shown == 0 {
            self.message = Some("your image matches: no region differs".into());
            return;
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
            "region {} {of}: {} pixels on {}",
            index + 1,
            region.pixels,
            objects(region)
        );
        self.region = Some(index);
        self.pick(x, y);
        self.message = Some(message);
    }
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
